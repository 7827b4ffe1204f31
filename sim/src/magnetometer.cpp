#include "cover/sim/magnetometer.hpp"

#include <Eigen/Geometry>

namespace cover::sim {

Magnetometer::Magnetometer(const MagnetometerParams& params, std::uint64_t seed)
    : params_(params), rng_(seed) {
  bias_gauss_ = white_noise(params_.bias_sigma_gauss);
}

Eigen::Vector3d Magnetometer::white_noise(double sigma) {
  return sigma * Eigen::Vector3d(unit_normal_(rng_), unit_normal_(rng_), unit_normal_(rng_));
}

MagnetometerSample Magnetometer::sample(const QuadrotorState& body, double stamp_s) {
  MagnetometerSample reading;
  reading.stamp_s = stamp_s;
  reading.field_flu_gauss =
      body.attitude.eigen().normalized().inverse() * params_.world_field_enu_gauss + bias_gauss_ +
      white_noise(params_.noise_gauss);
  return reading;
}

}  // namespace cover::sim
