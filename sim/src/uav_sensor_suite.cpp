#include "cover/sim/uav_sensor_suite.hpp"

#include <cmath>

#include "cover/sim/seeding.hpp"

namespace cover::sim {

namespace {

constexpr std::uint64_t kImuStream = 0;
constexpr std::uint64_t kBarometerStream = 1;
constexpr std::uint64_t kMagnetometerStream = 2;

// Physics steps per sample; 0 when `rate_hz` does not divide `physics_rate_hz`.
std::uint64_t period_steps(double physics_rate_hz, double rate_hz) {
  const double ratio = physics_rate_hz / rate_hz;
  const double whole = std::round(ratio);
  if (whole < 1.0 || std::abs(ratio - whole) > 1e-9 * ratio) return 0;
  return static_cast<std::uint64_t>(whole);
}

void check_divides(double physics_rate_hz, double rate_hz, const std::string& key) {
  config::check(period_steps(physics_rate_hz, rate_hz) > 0, key,
                "must divide the physics rate " + config::format_number(physics_rate_hz) + " Hz");
}

}  // namespace

void UavSensorParams::validate(const std::string& context, double physics_rate_hz) const {
  config::check_fields(*this, context);
  if (physics_rate_hz <= 0.0) return;
  check_divides(physics_rate_hz, imu.rate_hz, context + ".imu.rate_hz");
  check_divides(physics_rate_hz, barometer.rate_hz, context + ".barometer.rate_hz");
  check_divides(physics_rate_hz, magnetometer.rate_hz, context + ".magnetometer.rate_hz");
}

UavSensorSuite::UavSensorSuite(const UavSensorParams& params, double physics_rate_hz,
                               double gravity_m_s2, std::uint64_t seed)
    : imu_period_steps_((params.validate("uav_sensors", physics_rate_hz),
                         period_steps(physics_rate_hz, params.imu.rate_hz))),
      barometer_period_steps_(period_steps(physics_rate_hz, params.barometer.rate_hz)),
      magnetometer_period_steps_(period_steps(physics_rate_hz, params.magnetometer.rate_hz)),
      imu_(params.imu, gravity_m_s2, derive_seed(seed, kImuStream)),
      barometer_(params.barometer, derive_seed(seed, kBarometerStream)),
      magnetometer_(params.magnetometer, derive_seed(seed, kMagnetometerStream)) {}

UavSensorFrame UavSensorSuite::update(std::uint64_t step_index, double time_s,
                                      const QuadrotorState& body,
                                      const Eigen::Vector3d& acceleration_world_m_s2) {
  UavSensorFrame frame;
  if (step_index % imu_period_steps_ == 0) {
    frame.imu = imu_.sample(body, acceleration_world_m_s2, time_s);
  }
  if (step_index % barometer_period_steps_ == 0) {
    frame.barometer = barometer_.sample(body.position_m.z, time_s);
  }
  if (step_index % magnetometer_period_steps_ == 0) {
    frame.magnetometer = magnetometer_.sample(body, time_s);
  }
  return frame;
}

}  // namespace cover::sim
