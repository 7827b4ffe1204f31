#pragma once

#include <cstdint>
#include <string>

#include "cover/config/yaml_reader.hpp"

namespace cover::fc_bridge {

// cover-fc-bridge's settings (config/fc_bridge.yaml, section `fc_bridge`); the YAML file
// documents each one.
struct FcBridgeParams {
  // Normalised collective thrust (0..1) that hovers the vehicle, the estimator's start.
  // 9.81 / 20: the simulated quadrotor's nominal hover (full throttle gives 20 m/s^2).
  double hover_thrust = 0.4905;
  double hover_thrust_min = 0.15;  // the estimate stays within [min, max]
  double hover_thrust_max = 0.85;
  double hover_thrust_initial_std = 0.1;          // 1-sigma doubt about hover_thrust at start
  double hover_thrust_noise_per_sqrt_s = 0.0036;  // random walk of the true hover thrust
  double accel_noise_m_s2 = 1.0;                  // 1-sigma of the body z specific force
  double estimator_min_thrust = 0.1;              // below this commanded thrust the estimator rests
  double cmd_timeout_s = 0.1;                     // armed in offboard with no agent command: land
  double heartbeat_timeout_s = 1.5;               // no autopilot HEARTBEAT: link lost
  double ack_timeout_s = 0.25;     // a COMMAND_LONG unanswered this long is sent again
  int command_retries = 3;         // resends before "no answer"
  double offboard_stream_s = 1.0;  // setpoints stream this long before OFFBOARD
  double state_rate_hz = 10.0;     // cover/uav/U/fc
  int system_id = 0;               // the companion's MAVLink system id; 0: the autopilot's
  int component_id = 191;          // MAV_COMP_ID_ONBOARD_COMPUTER
  bool auto_arm = false;           // simulation only: arm without an operator
  double gravity_m_s2 = 9.81;

  static FcBridgeParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static FcBridgeParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::fc_bridge
