#pragma once

#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/sim/motor_quadrotor.hpp"
#include "cover/sim/uav_sensor_suite.hpp"

namespace cover::sim {

// A UAV as a real firmware sees it in simulation: the motor-level plant it flies and the
// sensors its estimator reads. One file per firmware (config/sim/firmware_uav_px4.yaml,
// firmware_uav_arducopter.yaml), section `firmware_uav`.
struct FirmwareUavParams {
  MotorQuadrotorParams plant;
  UavSensorParams sensors;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("plant", self.plant, Field("", "the motor-level quadrotor (motor_quadrotor.hpp)"));
    visit("sensors", self.sensors,
          Field("", "IMU, barometer, magnetometer (uav_sensor_suite.hpp)"));
  }

  // The file's section `firmware_uav` (required); validated, the sensor rates against
  // `physics_rate_hz` (the world's) when it is given.
  static FirmwareUavParams load_file(const std::string& path, double physics_rate_hz = 0.0);
  // Throws config::ConfigError naming "<context>.<key>".
  void validate(const std::string& context = "firmware_uav", double physics_rate_hz = 0.0) const;
};

}  // namespace cover::sim
