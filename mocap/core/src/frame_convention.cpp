#include "cover/mocap/frame_convention.hpp"

#include <cmath>

namespace cover::mocap {

WorldPose to_world(const std::array<double, 3>& position, const std::array<double, 4>& xyzw,
                   const std::string& up_axis, const std::string& units) {
  WorldPose pose;
  const double scale = units == "mm" ? 1e-3 : 1.0;
  pose.position_m = scale * Eigen::Vector3d(position[0], position[1], position[2]);
  pose.attitude = Eigen::Quaterniond(xyzw[3], xyzw[0], xyzw[1], xyzw[2]).normalized();
  if (up_axis == "y") {
    const Eigen::Quaterniond y_up_to_world(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()));
    pose.position_m = y_up_to_world * pose.position_m;
    pose.attitude = (y_up_to_world * pose.attitude * y_up_to_world.inverse()).normalized();
  }
  return pose;
}

}  // namespace cover::mocap
