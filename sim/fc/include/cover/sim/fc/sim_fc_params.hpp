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

// The streams an autopilot sends on its companion link until MAV_CMD_SET_MESSAGE_INTERVAL
// changes one (0: not sent). At most one frame of a message per control period: the
// autopilot is stepped at the control rate.
struct StreamRates {
  double heartbeat_hz = 1.0;
  double highres_imu_hz = 0.0;
  double attitude_quaternion_hz = 0.0;
  double attitude_hz = 0.0;  // ATTITUDE (30): Euler angles
  double attitude_target_hz = 0.0;
  double extended_sys_state_hz = 0.0;
  double sys_status_hz = 0.0;
  double battery_status_hz = 0.0;
  double estimator_hz = 0.0;           // ESTIMATOR_STATUS (PX4) / EKF_STATUS_REPORT (ArduPilot)
  double local_position_ned_hz = 0.0;  // LOCAL_POSITION_NED: sent when asked
  // PX4 only: ALTITUDE (141) and VFR_HUD (74), two of the ~25 message types real PX4 streams
  // that COVER's codec does not know: a bridge must skip them whole.
  double codec_unknown_hz = 0.0;

  // PX4's "onboard" link (mavlink_main.cpp MAVLINK_MODE_ONBOARD), as measured from PX4 SITL
  // (docs/autopilots.md, measured on real SITL): ATTITUDE 98, ATTITUDE_QUATERNION and HIGHRES_IMU
  // 49, ...
  static StreamRates px4_onboard();
  // ArduCopter: every stream rate 0 on every port; HEARTBEAT only.
  static StreamRates ardupilot_default() { return StreamRates{}; }

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    const auto rate = [](const char* doc) {
      return Field("Hz", doc).at_least(0.0).at_most(1000.0);
    };
    visit("heartbeat_hz", self.heartbeat_hz, rate("HEARTBEAT"));
    visit("highres_imu_hz", self.highres_imu_hz, rate("HIGHRES_IMU, the UAV's own IMU"));
    visit("attitude_quaternion_hz", self.attitude_quaternion_hz, rate("ATTITUDE_QUATERNION"));
    visit("attitude_hz", self.attitude_hz, rate("ATTITUDE (Euler angles)"));
    visit("attitude_target_hz", self.attitude_target_hz,
          rate("ATTITUDE_TARGET, what the rate loop flies"));
    visit("extended_sys_state_hz", self.extended_sys_state_hz,
          rate("EXTENDED_SYS_STATE, the landed state"));
    visit("sys_status_hz", self.sys_status_hz, rate("SYS_STATUS: sensors, battery"));
    visit("battery_status_hz", self.battery_status_hz, rate("BATTERY_STATUS"));
    visit("estimator_hz", self.estimator_hz,
          rate("ESTIMATOR_STATUS (PX4) / EKF_STATUS_REPORT (ArduPilot)"));
    visit("local_position_ned_hz", self.local_position_ned_hz,
          rate("LOCAL_POSITION_NED, the estimate's position and velocity"));
    visit("codec_unknown_hz", self.codec_unknown_hz,
          rate("PX4: ALTITUDE and VFR_HUD, message types COVER's codec does not know"));
  }
};

// The simulated PX4: its parameters (answered to PARAM_REQUEST_READ with PX4's types; the
// behavioural ones drive the simulation) and its stream rates.
struct Px4Params {
  StreamRates streams = StreamRates::px4_onboard();
  double com_of_loss_t_s = 1.0;      // COM_OF_LOSS_T: offboard loss -> land (no GPS: descend)
  int com_obl_rc_act = 0;            // COM_OBL_RC_ACT: reported only (the simulation descends)
  double mpc_thr_hover = 0.5;        // MPC_THR_HOVER: reported only
  double com_disarm_prflt_s = 10.0;  // COM_DISARM_PRFLT: auto-disarm before take-off (<= 0: never)
  double com_disarm_land_s = 2.0;    // COM_DISARM_LAND: auto-disarm after landing (<= 0: never)
  int com_rc_in_mode = 1;            // COM_RC_IN_MODE: reported only
  int nav_dll_act = 0;               // NAV_DLL_ACT: reported only
  double estimator_align_s = 0.0;    // simulated time from boot to an aligned attitude estimate

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("streams", self.streams,
          Field("", "streams on the companion link until SET_MESSAGE_INTERVAL changes them"));
    visit("com_of_loss_t_s", self.com_of_loss_t_s,
          Field("s", "COM_OF_LOSS_T: no setpoint this long in OFFBOARD, armed: descend and land")
              .at_least(0.01)
              .at_most(60.0));
    visit("com_obl_rc_act", self.com_obl_rc_act,
          Field("", "COM_OBL_RC_ACT (reported: the simulated PX4 always descends)")
              .at_least(0.0)
              .at_most(7.0));
    visit("mpc_thr_hover", self.mpc_thr_hover,
          Field("", "MPC_THR_HOVER (reported only)").at_least(0.1).at_most(0.8));
    visit("com_disarm_prflt_s", self.com_disarm_prflt_s,
          Field("s",
                "COM_DISARM_PRFLT: armed without taking off this long + 1 s spool-up: disarm "
                "(<= 0 never)")
              .at_least(-1.0)
              .at_most(20.0));
    visit("com_disarm_land_s", self.com_disarm_land_s,
          Field("s", "COM_DISARM_LAND: landed this long after a take-off: disarm (<= 0 never)")
              .at_least(-1.0)
              .at_most(20.0));
    visit("com_rc_in_mode", self.com_rc_in_mode,
          Field("", "COM_RC_IN_MODE (reported only)").at_least(0.0).at_most(4.0));
    visit("nav_dll_act", self.nav_dll_act,
          Field("", "NAV_DLL_ACT (reported only)").at_least(0.0).at_most(6.0));
    visit("estimator_align_s", self.estimator_align_s,
          Field("s", "boot to an aligned attitude estimate (ESTIMATOR_STATUS, SYS_STATUS AHRS)")
              .at_least(0.0)
              .at_most(600.0));
  }
};

// The simulated ArduCopter: as Px4Params.
struct ArduPilotParams {
  StreamRates streams = StreamRates::ardupilot_default();
  int atc_angle_boost = 0;         // ATC_ANGLE_BOOST: 1 multiplies the thrust by 1/cos(tilt)
  int guid_options = 8;            // GUID_OPTIONS: reported only (bit 3: thrust is thrust)
  double guid_timeout_s = 3.0;     // GUID_TIMEOUT: no setpoint -> level, hold height
  int fs_gcs_enable = 5;           // FS_GCS_ENABLE: 0 none, else LAND (no position: no RTL)
  double fs_gcs_timeout_s = 5.0;   // FS_GCS_TIMEOUT: the watched HEARTBEAT silent this long
  int mav_gcs_sysid = 0;           // MAV_GCS_SYSID: whose HEARTBEAT is watched; 0: our own id
  int fs_thr_enable = 0;           // FS_THR_ENABLE: reported only
  double mot_thst_hover = 0.35;    // MOT_THST_HOVER: reported only
  int disarm_delay_s = 10;         // DISARM_DELAY: landed at zero throttle this long: disarm
  double estimator_align_s = 1.0;  // boot to EKF3 tilt alignment

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("streams", self.streams,
          Field("", "streams on the companion link until SET_MESSAGE_INTERVAL changes them")
              .without({"codec_unknown_hz"}));
    visit("atc_angle_boost", self.atc_angle_boost,
          Field("", "ATC_ANGLE_BOOST: 1 divides the thrust by cos(tilt) (COVER needs 0)")
              .at_least(0.0)
              .at_most(1.0));
    visit("guid_options", self.guid_options,
          Field("", "GUID_OPTIONS (reported only; COVER needs bit 3, thrust as thrust)")
              .at_least(0.0)
              .at_most(65535.0));
    visit("guid_timeout_s", self.guid_timeout_s,
          Field("s", "GUID_TIMEOUT: no setpoint this long in GUIDED_NOGPS: level, height held")
              .at_least(0.1)
              .at_most(60.0));
    visit("fs_gcs_enable", self.fs_gcs_enable,
          Field("",
                "FS_GCS_ENABLE: 0 no GCS failsafe; else LAND when the watched HEARTBEAT stops "
                "(armed, in the air; on the ground it disarms). Without a position ArduPilot's "
                "RTL, SmartRTL and Brake fall back to LAND, so every action lands here")
              .at_least(0.0)
              .at_most(7.0));
    visit("fs_gcs_timeout_s", self.fs_gcs_timeout_s,
          Field("s", "FS_GCS_TIMEOUT: the watched HEARTBEAT silent this long: the GCS failsafe")
              .at_least(2.0)
              .at_most(120.0));
    visit("mav_gcs_sysid", self.mav_gcs_sysid,
          Field("",
                "MAV_GCS_SYSID: the system whose HEARTBEAT the GCS failsafe watches; 0: the "
                "vehicle's own id, which a companion (COVER's bridge) speaks with")
              .at_least(0.0)
              .at_most(255.0));
    visit("fs_thr_enable", self.fs_thr_enable,
          Field("", "FS_THR_ENABLE (reported only)").at_least(0.0).at_most(7.0));
    visit("mot_thst_hover", self.mot_thst_hover,
          Field("", "MOT_THST_HOVER (reported only)").at_least(0.125).at_most(0.6875));
    visit("disarm_delay_s", self.disarm_delay_s,
          Field("s", "DISARM_DELAY: armed, landed, zero throttle this long: disarm (0 never)")
              .at_least(0.0)
              .at_most(127.0));
    visit("estimator_align_s", self.estimator_align_s,
          Field("s", "boot to EKF3 tilt alignment (EKF_STATUS_REPORT, SYS_STATUS AHRS)")
              .at_least(0.0)
              .at_most(600.0));
  }
};

// The system whose HEARTBEAT the simulated ArduPilot's GCS failsafe watches.
inline std::uint8_t watched_gcs_sysid(const ArduPilotParams& p, std::uint8_t own_system_id) {
  return p.mav_gcs_sysid == 0 ? own_system_id : static_cast<std::uint8_t>(p.mav_gcs_sysid);
}

// The simulated autopilots (config/sim/sim_fc.yaml, section `sim_fc`): their MAVLink
// identities, each firmware's parameters and streams, the battery.
struct SimFcParams {
  // UAV u's autopilot is system system_id_base + u, component 1: a bridge must learn it
  // from the HEARTBEAT, never assume 1.
  int system_id_base = 1;
  // UGV k's rover autopilot (its IMU stream) is system ugv_system_id_base + k.
  int ugv_system_id_base = 101;
  double land_speed_m_s = 0.5;  // PX4 MPC_LAND_SPEED / ArduPilot LAND_SPEED
  Px4Params px4;
  ArduPilotParams ardupilot;
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
    visit("land_speed_m_s", self.land_speed_m_s,
          Field("m/s", "PX4 MPC_LAND_SPEED / ArduPilot LAND_SPEED").at_least(0.05).at_most(3.0));
    visit("px4", self.px4, Field("", "the simulated PX4 (cover-sim --fc px4)"));
    visit("ardupilot", self.ardupilot, Field("", "the simulated ArduCopter (--fc ardupilot)"));
    visit("battery", self.battery, Field("", "the flight battery behind SYS_STATUS"));
  }

  static SimFcParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static SimFcParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::sim::fc
