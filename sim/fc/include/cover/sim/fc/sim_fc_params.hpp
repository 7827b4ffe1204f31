#pragma once

#include <cstdint>
#include <string>

#include "cover/config/param_fields.hpp"
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

  // Each field once (config/param_fields.hpp); cell_full_v above cell_empty_v is checked
  // by SimFcParams::validate.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("cells", self.cells, Field("", "cells in series").at_least(1.0).at_most(10.0));
    visit("capacity_mah", self.capacity_mah,
          Field("mAh", "usable charge").at_least(1.0).at_most(1e6));
    visit("cell_full_v", self.cell_full_v,
          Field("V", "open-circuit cell voltage when full, above cell_empty_v")
              .at_least(2.0)
              .at_most(5.0));
    visit("cell_empty_v", self.cell_empty_v,
          Field("V", "open-circuit cell voltage when empty").at_least(2.0).at_most(5.0));
    visit("hover_current_a", self.hover_current_a,
          Field("A", "motor current at hover thrust; scales with thrust^1.5")
              .at_least(0.0)
              .at_most(500.0));
    visit("idle_current_a", self.idle_current_a,
          Field("A", "electronics, armed or not").at_least(0.0).at_most(50.0));
    visit("internal_resistance_ohm", self.internal_resistance_ohm,
          Field("ohm", "the pack's: voltage sag under load").at_least(0.0).at_most(1.0));
  }
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

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    // System ids 1..250: 0 is broadcast, 251..255 are ground stations and tools by convention.
    visit("system_id_base", self.system_id_base,
          Field("", "UAV u's autopilot is MAVLink system system_id_base + u")
              .at_least(1.0)
              .at_most(247.0)
              .hint("UAVs 0..3 take system_id_base + u <= 250"));
    visit("ugv_system_id_base", self.ugv_system_id_base,
          Field("",
                "UGV k's rover autopilot is system ugv_system_id_base + k; apart from the "
                "UAVs' ids")
              .at_least(1.0)
              .at_most(243.0)
              .hint("UGVs 0..7 take ugv_system_id_base + k <= 250"));
    visit("heartbeat_rate_hz", self.heartbeat_rate_hz,
          Field("Hz", "HEARTBEAT").at_least(0.1).at_most(1000.0));
    visit("attitude_rate_hz", self.attitude_rate_hz,
          Field("Hz", "ATTITUDE_QUATERNION").at_least(0.1).at_most(1000.0));
    visit("highres_imu_rate_hz", self.highres_imu_rate_hz,
          Field("Hz", "HIGHRES_IMU, the UAV's own IMU").at_least(0.1).at_most(1000.0));
    visit("attitude_target_rate_hz", self.attitude_target_rate_hz,
          Field("Hz", "ATTITUDE_TARGET, what the rate loop flies").at_least(0.1).at_most(1000.0));
    visit("extended_sys_state_rate_hz", self.extended_sys_state_rate_hz,
          Field("Hz", "EXTENDED_SYS_STATE, the landed state").at_least(0.1).at_most(1000.0));
    visit("sys_status_rate_hz", self.sys_status_rate_hz,
          Field("Hz", "SYS_STATUS and BATTERY_STATUS").at_least(0.1).at_most(1000.0));
    visit("com_of_loss_t_s", self.com_of_loss_t_s,
          Field("s", "PX4 COM_OF_LOSS_T: no setpoint this long in OFFBOARD, armed: land")
              .at_least(0.01)
              .at_most(60.0));
    visit("guid_timeout_s", self.guid_timeout_s,
          Field("s",
                "ArduPilot GUID_TIMEOUT: no setpoint this long in GUIDED_NOGPS: level, "
                "height held")
              .at_least(0.1)
              .at_most(60.0));
    visit("guid_level_hold_s", self.guid_level_hold_s,
          Field("s", "ArduPilot: levelled this long after GUID_TIMEOUT, then LAND")
              .at_least(0.0)
              .at_most(600.0));
    visit("land_speed_m_s", self.land_speed_m_s,
          Field("m/s", "PX4 MPC_LAND_SPEED / ArduPilot LAND_SPEED").at_least(0.05).at_most(3.0));
    visit("offboard_stream_min_rate_hz", self.offboard_stream_min_rate_hz,
          Field("Hz", "OFFBOARD / GUIDED_NOGPS only after setpoints faster than this ...")
              .at_least(0.1)
              .at_most(100.0));
    visit("offboard_stream_min_s", self.offboard_stream_min_s,
          Field("s", "... for this long").at_least(0.0).at_most(10.0));
    visit("battery", self.battery, Field("", "the flight battery behind SYS_STATUS"));
  }

  static SimFcParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static SimFcParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::sim::fc
