#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "cover/config/param_fields.hpp"
#include "cover/sim/sensor_rate_field.hpp"
#include "cover/vocabulary/quadrotor_state.hpp"

namespace cover::sim {

// The UAV's own IMU, the one a firmware's estimator reads (PX4's HIL_SENSOR, ArduPilot's
// JSON `imu`): specific force (gravity included: at rest [0, 0, +g]) and body rates, in
// body FLU, with white noise and a constant bias drawn once from the seed.
struct UavImuParams {
  double rate_hz = 250.0;  // PX4 SITL's IMU_INTEG_RATE default
  double specific_force_noise_m_s2 = 0.05;
  double angular_velocity_noise_rad_s = 0.005;
  double specific_force_bias_sigma_m_s2 = 0.02;
  double angular_velocity_bias_sigma_rad_s = 0.002;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("rate_hz", self.rate_hz,
          sensor_rate_field("sample rate (PX4 SITL: 250); must divide the physics rate"));
    visit("specific_force_noise_m_s2", self.specific_force_noise_m_s2,
          Field("m/s^2", "accelerometer white noise 1-sigma").at_least(0.0).at_most(10.0));
    visit("angular_velocity_noise_rad_s", self.angular_velocity_noise_rad_s,
          Field("rad/s", "gyro white noise 1-sigma").at_least(0.0).at_most(1.0));
    visit("specific_force_bias_sigma_m_s2", self.specific_force_bias_sigma_m_s2,
          Field("m/s^2", "1-sigma of the constant accelerometer bias").at_least(0.0).at_most(2.0));
    visit("angular_velocity_bias_sigma_rad_s", self.angular_velocity_bias_sigma_rad_s,
          Field("rad/s", "1-sigma of the constant gyro bias").at_least(0.0).at_most(0.5));
  }
};

struct UavImuSample {
  double stamp_s = 0.0;
  Eigen::Vector3d specific_force_flu_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_flu_rad_s = Eigen::Vector3d::Zero();
};

// Noise-free reading: R^T (a_world + g e_z) and the body rate.
UavImuSample true_uav_imu_sample(const QuadrotorState& body,
                                 const Eigen::Vector3d& acceleration_world_m_s2,
                                 double gravity_m_s2, double stamp_s);

class UavImu {
 public:
  UavImu(const UavImuParams& params, double gravity_m_s2, std::uint64_t seed);

  // A reading of `body` whose world-frame acceleration is `acceleration_world_m_s2`.
  UavImuSample sample(const QuadrotorState& body, const Eigen::Vector3d& acceleration_world_m_s2,
                      double stamp_s);

  const Eigen::Vector3d& specific_force_bias_m_s2() const { return specific_force_bias_m_s2_; }
  const Eigen::Vector3d& angular_velocity_bias_rad_s() const {
    return angular_velocity_bias_rad_s_;
  }

 private:
  Eigen::Vector3d white_noise(double sigma);

  UavImuParams params_;
  double gravity_m_s2_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  Eigen::Vector3d specific_force_bias_m_s2_;
  Eigen::Vector3d angular_velocity_bias_rad_s_;
};

}  // namespace cover::sim
