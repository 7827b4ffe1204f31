#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/sim/barometer.hpp"
#include "cover/sim/magnetometer.hpp"
#include "cover/sim/uav_imu.hpp"
#include "cover/vocabulary/quadrotor_state.hpp"

namespace cover::sim {

// The sensors a real firmware's estimator reads from its simulator, each at its own rate
// (PX4 SITL: IMU 250 Hz, magnetometer 100 Hz, barometer 50 Hz). Plain data in sim's frames
// (ENU world, FLU body): the MAVLink and JSON links convert to NED / FRD.
struct UavSensorParams {
  UavImuParams imu;
  BarometerParams barometer;
  MagnetometerParams magnetometer;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("imu", self.imu, Field("", "the UAV's IMU"));
    visit("barometer", self.barometer, Field("", "the UAV's barometer"));
    visit("magnetometer", self.magnetometer, Field("", "the UAV's magnetometer"));
  }

  // Throws config::ConfigError naming "<context>.<key>"; with `physics_rate_hz`, also
  // when a rate does not divide it.
  void validate(const std::string& context = "uav_sensors", double physics_rate_hz = 0.0) const;
};

// What one physics step produced: each sensor's sample on the steps it is due.
struct UavSensorFrame {
  std::optional<UavImuSample> imu;
  std::optional<BarometerSample> barometer;
  std::optional<MagnetometerSample> magnetometer;
};

class UavSensorSuite {
 public:
  // Throws config::ConfigError when a rate does not divide `physics_rate_hz`. The three
  // sensors draw from their own streams of `seed` (seeding.hpp).
  UavSensorSuite(const UavSensorParams& params, double physics_rate_hz, double gravity_m_s2,
                 std::uint64_t seed);

  // After physics step `step_index` (time = step_index / physics rate): samples the sensors
  // due on it. `acceleration_world_m_s2` is the body's over the step (the plant's, or the
  // deck's while resting on one).
  UavSensorFrame update(std::uint64_t step_index, double time_s, const QuadrotorState& body,
                        const Eigen::Vector3d& acceleration_world_m_s2);

  std::uint64_t imu_period_steps() const { return imu_period_steps_; }
  std::uint64_t barometer_period_steps() const { return barometer_period_steps_; }
  std::uint64_t magnetometer_period_steps() const { return magnetometer_period_steps_; }

 private:
  std::uint64_t imu_period_steps_;
  std::uint64_t barometer_period_steps_;
  std::uint64_t magnetometer_period_steps_;
  UavImu imu_;
  Barometer barometer_;
  Magnetometer magnetometer_;
};

}  // namespace cover::sim
