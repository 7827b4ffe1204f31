#pragma once
// ArduPilot SITL's JSON backend, physics -> firmware: the state line after each frame
// (libraries/SITL/examples/JSON/readme.md). The firmware takes the text between the last
// two newlines of what it has received, so the line is "\n{...}\n": the leading newline is
// required. Its parser looks keys up with strstr and reads vectors with
// sscanf("[%f, %f, %f]"), so the writer emits exactly that form.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "cover/firmware_link/plant_sample.hpp"
#include "cover/sim/uav_imu.hpp"

namespace cover::firmware_link {

// In ArduPilot's frames: NED earth, FRD body.
struct ArduPilotJsonState {
  double timestamp_s = 0.0;  // the physics clock, the firmware's clock in lockstep
  Eigen::Vector3d gyro_frd_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_frd_m_s2 = Eigen::Vector3d::Zero();  // specific force: (0, 0, -g) at rest
  Eigen::Vector3d position_ned_m = Eigen::Vector3d::Zero();  // from home (the world origin)
  Eigen::Vector3d velocity_ned_m_s = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude_frd_to_ned = Eigen::Quaterniond::Identity();
  // Lockstep: the firmware does not pace itself to the wall clock (use_time_sync false).
  bool no_time_sync = false;
};

// The plant's state after a step (ENU / FLU) as ArduPilot reads it; `imu` is the IMU
// sample to report (the step's, or the last one when the IMU is slower than the physics).
ArduPilotJsonState ardupilot_json_state(const PlantSample& sample, const sim::UavImuSample& imu,
                                        bool no_time_sync);

// "\n{json}\n" with timestamp, imu.gyro, imu.accel_body, position, velocity, quaternion
// (w first, canonical w >= 0) and, when set, "no_time_sync":1. Throws std::invalid_argument
// on a non-finite value: the firmware's atof would read "nan" and its estimator diverge.
std::string write_ardupilot_json(const ArduPilotJsonState& state);

}  // namespace cover::firmware_link
