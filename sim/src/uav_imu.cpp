#include "cover/sim/uav_imu.hpp"

#include <Eigen/Geometry>

namespace cover::sim {

UavImuSample true_uav_imu_sample(const QuadrotorState& body,
                                 const Eigen::Vector3d& acceleration_world_m_s2,
                                 double gravity_m_s2, double stamp_s) {
  UavImuSample sample;
  sample.stamp_s = stamp_s;
  const Eigen::Vector3d proper_acceleration =
      acceleration_world_m_s2 + Eigen::Vector3d(0.0, 0.0, gravity_m_s2);
  sample.specific_force_flu_m_s2 =
      body.attitude.eigen().normalized().inverse() * proper_acceleration;
  sample.angular_velocity_flu_rad_s = body.body_rate_rad_s.eigen();
  return sample;
}

UavImu::UavImu(const UavImuParams& params, double gravity_m_s2, std::uint64_t seed)
    : params_(params), gravity_m_s2_(gravity_m_s2), rng_(seed) {
  specific_force_bias_m_s2_ = white_noise(params_.specific_force_bias_sigma_m_s2);
  angular_velocity_bias_rad_s_ = white_noise(params_.angular_velocity_bias_sigma_rad_s);
}

Eigen::Vector3d UavImu::white_noise(double sigma) {
  return sigma * Eigen::Vector3d(unit_normal_(rng_), unit_normal_(rng_), unit_normal_(rng_));
}

UavImuSample UavImu::sample(const QuadrotorState& body,
                            const Eigen::Vector3d& acceleration_world_m_s2, double stamp_s) {
  UavImuSample reading = true_uav_imu_sample(body, acceleration_world_m_s2, gravity_m_s2_, stamp_s);
  reading.specific_force_flu_m_s2 +=
      specific_force_bias_m_s2_ + white_noise(params_.specific_force_noise_m_s2);
  reading.angular_velocity_flu_rad_s +=
      angular_velocity_bias_rad_s_ + white_noise(params_.angular_velocity_noise_rad_s);
  return reading;
}

}  // namespace cover::sim
