#pragma once

#include <cstdint>
#include <string>

#include "cover/config/yaml_reader.hpp"

namespace cover::sim::fc {

// A battery that empties with the current the motors draw: the voltage the SYS_STATUS and
// BATTERY_STATUS streams report (a bridge reads it; nothing in the plant depends on it).
struct BatteryParams {
  int cells = 4;
  double capacity_mah = 5000.0;
  double cell_full_v = 4.2;               // open-circuit cell voltage, full
  double cell_empty_v = 3.5;              // open-circuit cell voltage, empty
  double hover_current_a = 12.0;          // drawn at hover thrust, scales with thrust^1.5
  double idle_current_a = 0.5;            // electronics, armed or not
  double internal_resistance_ohm = 0.02;  // the pack's: the sag under load
};

// The simulated autopilots (config/sim/sim_fc.yaml, section `sim_fc`): their MAVLink
// identities, stream rates and the autopilot parameters the tests exercise.
struct SimFcParams {
  // UAV u's autopilot is system system_id_base + u, component 1: a bridge must learn it
  // from the HEARTBEAT, never assume 1.
  int system_id_base = 1;
  // UGV k's rover autopilot (its IMU stream) is system ugv_system_id_base + k.
  int ugv_system_id_base = 101;
  // Streams, Hz; at most one frame per control period (cover-sim steps the autopilot at
  // the control rate).
  double heartbeat_rate_hz = 1.0;
  double attitude_rate_hz = 50.0;  // ATTITUDE_QUATERNION
  double highres_imu_rate_hz = 100.0;
  double attitude_target_rate_hz = 10.0;
  double extended_sys_state_rate_hz = 5.0;
  double sys_status_rate_hz = 1.0;  // SYS_STATUS and BATTERY_STATUS
  // PX4 COM_OF_LOSS_T: no setpoint for this long in OFFBOARD, armed -> land (no GPS: descend).
  double com_of_loss_t_s = 1.0;
  // ArduPilot GUID_TIMEOUT: no setpoint for this long in GUIDED_NOGPS -> level, height held.
  double guid_timeout_s = 3.0;
  // ArduPilot: levelled this long after GUID_TIMEOUT, then LAND. ArduPilot itself would hold
  // level until the pilot acts; the simulator has no pilot.
  double guid_level_hold_s = 2.0;
  double land_speed_m_s = 0.5;  // PX4 MPC_LAND_SPEED / ArduPilot LAND_SPEED
  // OFFBOARD / GUIDED_NOGPS is granted only after setpoints streamed faster than
  // offboard_stream_min_rate_hz for offboard_stream_min_s.
  double offboard_stream_min_rate_hz = 2.0;
  double offboard_stream_min_s = 1.0;
  BatteryParams battery;

  static SimFcParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static SimFcParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::sim::fc
