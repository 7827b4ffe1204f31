#include "cover/sim/frame_conventions.hpp"

namespace cover::sim {

Eigen::Vector3d enu_to_ned(const Eigen::Vector3d& v) {
  return {v.y(), v.x(), -v.z()};
}

Eigen::Vector3d flu_to_frd(const Eigen::Vector3d& v) {
  return {v.x(), -v.y(), -v.z()};
}

// R_ned<-frd = T R_enu<-flu F, with T the ENU -> NED map and F the FRD -> FLU map.
Eigen::Quaterniond ned_frd_attitude(const Eigen::Quaterniond& enu_flu) {
  Eigen::Matrix3d ned_from_enu;
  ned_from_enu << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  const Eigen::Matrix3d flu_from_frd = Eigen::Vector3d(1, -1, -1).asDiagonal();
  Eigen::Quaterniond q(ned_from_enu * enu_flu.toRotationMatrix() * flu_from_frd);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  return q;
}

}  // namespace cover::sim
