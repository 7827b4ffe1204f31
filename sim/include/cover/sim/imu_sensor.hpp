#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/odometry_sensor.hpp"
#include "cover/sim/sensor_rate_field.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/speed_estimator.hpp"
#include "cover/ugv/ugv_sensor_pipeline.hpp"
#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

// Each UGV's IMU: specific force (gravity included) and gyro in G_k, white noise plus a
// constant bias drawn once per UGV from the seed (a turned-on MEMS IMU's bias).
struct ImuSensorParams {
  double rate_hz = 200.0;  // must divide the physics rate
  double specific_force_noise_m_s2 = 0.05;
  double angular_velocity_noise_rad_s = 0.005;
  double specific_force_bias_sigma_m_s2 = 0.02;
  double angular_velocity_bias_sigma_rad_s = 0.002;
  // Probability that a sample is corrupted (NaN in one axis): exercises the filter's
  // rejection path end to end. 0 by default.
  double fault_probability = 0.0;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("rate_hz", self.rate_hz,
          sensor_rate_field("sample rate; must divide world.physics_rate_hz"));
    visit("specific_force_noise_m_s2", self.specific_force_noise_m_s2,
          Field("m/s^2", "accelerometer white noise 1-sigma").at_least(0.0).at_most(10.0));
    visit("angular_velocity_noise_rad_s", self.angular_velocity_noise_rad_s,
          Field("rad/s", "gyro white noise 1-sigma").at_least(0.0).at_most(1.0));
    visit("specific_force_bias_sigma_m_s2", self.specific_force_bias_sigma_m_s2,
          Field("m/s^2", "1-sigma of the constant accelerometer bias drawn per UGV")
              .at_least(0.0)
              .at_most(2.0));
    visit("angular_velocity_bias_sigma_rad_s", self.angular_velocity_bias_sigma_rad_s,
          Field("rad/s", "1-sigma of the constant gyro bias drawn per UGV")
              .at_least(0.0)
              .at_most(0.5));
    visit("fault_probability", self.fault_probability,
          Field("", "probability that a sample is corrupted (NaN), to test rejection")
              .at_least(0.0)
              .at_most(1.0));
  }

  static ImuSensorParams load(cover::config::YamlReader& reader);
  // Throws config::ConfigError naming "<context>.<key>".
  void validate(const std::string& context = "imu") const;
};

// Noise-free IMU reading of a planar UGV: R^T (a_world + g e_z) and [0, 0, yaw rate].
ugv::ImuSample true_imu_sample(const UgvState& ugv, double gravity_m_s2, double stamp_s);

struct ImuReading {
  ugv::ImuSample raw;         // what the IMU chip outputs (with the wheel speed when sampled)
  ugv::FilteredImu filtered;  // what the UGV agent publishes (a, Omega, beta)
  ugv::SpeedEstimate speed;   // and the forward speed estimate it publishes beside them
  ugv::ImuFilterStatus status = ugv::ImuFilterStatus::Started;
};

class ImuSensor {
 public:
  ImuSensor(const ImuSensorParams& params, const ugv::ImuFilterParams& filter_params,
            const ugv::SpeedEstimatorParams& speed_params, double physics_rate_hz, int ugv_count,
            double gravity_m_s2, std::uint64_t seed);

  // Call after every physics step, after `odometry.update`: samples every UGV's IMU at
  // the sensor rate, attaches the wheel speed sampled on the same step, and runs the UGV
  // agent's pipeline (filter, speed estimate) on it.
  void update(const WorldState& world, const OdometrySensor& odometry);

  bool has_reading() const { return has_reading_; }
  // 0 <= ugv_index < ugv count; meaningful once has_reading().
  const ImuReading& latest(int ugv_index) const { return latest_[ugv_index]; }

 private:
  struct UgvImu {
    std::mt19937_64 rng;
    std::normal_distribution<double> unit_normal{0.0, 1.0};
    std::uniform_real_distribution<double> unit_uniform{0.0, 1.0};
    Eigen::Vector3d specific_force_bias_m_s2 = Eigen::Vector3d::Zero();
    Eigen::Vector3d angular_velocity_bias_rad_s = Eigen::Vector3d::Zero();
    ugv::UgvSensorPipeline pipeline;
  };
  static Eigen::Vector3d white_noise(UgvImu& imu, double sigma);

  ImuSensorParams params_;
  std::uint64_t sample_period_steps_;
  int ugv_count_;
  double gravity_m_s2_;
  std::array<UgvImu, kMaxUgvs> imus_;
  std::array<ImuReading, kMaxUgvs> latest_{};
  bool has_reading_ = false;
};

}  // namespace cover::sim
