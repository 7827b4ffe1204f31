#include <cmath>

#include "cover/fc_bridge/parameter_check.hpp"

// What COVER needs of each autopilot's parameters, and why (docs/autopilots.md; the
// firmware sources behind each: the study in docs/flight-controller.md).
namespace cover::fc_bridge {
namespace {

bool is_zero(double value) {
  return value == 0.0;
}
bool thrust_is_thrust(double value) {
  return (static_cast<long>(std::lround(value)) & 8) != 0;  // GUID_OPTIONS bit 3
}
bool within_one_second(double value) {
  return value > 0.0 && value <= 1.0;
}
bool keeps_flying(double value) {
  return value != 6.0 && value != 7.0;
}  // not terminate/disarm
bool mavlink_control_allowed(double value) {
  return value != 0.0;
}
bool guided_timeout_short(double value) {
  return value > 0.0 && value <= 3.0;
}
bool lands(double value) {
  return value == 5.0;
}  // FS_GCS_ENABLE 5: Land (RTL and SmartRTL need a position COVER does not give)
bool gcs_timeout_short(double value) {
  return value > 0.0 && value <= 5.0;
}
// ArduPilot's GCS failsafe watches the HEARTBEATs of this one system id.
bool watches_the_bridge(double value, const ParameterContext& context) {
  return context.bridge_system_id != 0 && value == static_cast<double>(context.bridge_system_id);
}

std::vector<ParameterRule> px4_rules() {
  return {
      {{"COM_OF_LOSS_T"},
       ParameterWeight::Advisory,
       "> 0 and <= 1 s",
       "PX4's own offboard-loss delay: if the bridge dies, PX4 takes the UAV back after it "
       "(the bridge itself lands the UAV within cmd_timeout_s of the agent's silence)",
       within_one_second},
      {{"COM_OBL_RC_ACT"},
       ParameterWeight::Blocking,
       "not 6 (terminate) or 7 (disarm)",
       "what PX4 does when COVER's setpoints stop: terminate or disarm drops the UAV",
       keeps_flying},
      {{"MPC_THR_HOVER"},
       ParameterWeight::Info,
       "any (the vehicle's hover thrust)",
       "the hover thrust PX4 assumes; the bridge's estimate can start from it",
       nullptr},
      {{"COM_DISARM_PRFLT"},
       ParameterWeight::Info,
       "any (< 0: never)",
       "PX4 disarms this long (+1 s spool-up) after arming if the UAV does not take off: "
       "arm within it of the task's start",
       nullptr},
      {{"COM_DISARM_LAND"},
       ParameterWeight::Info,
       "any (< 0: never)",
       "PX4 disarms this long after it detects a landing, on a deck too",
       nullptr},
      {{"COM_RC_IN_MODE"},
       ParameterWeight::Advisory,
       "not 0 without an RC receiver",
       "0 (RC only) makes an RC receiver an arming requirement",
       mavlink_control_allowed},
      {{"NAV_DLL_ACT"},
       ParameterWeight::Advisory,
       "0",
       "> 0 makes a ground-station link an arming requirement and its loss a failsafe that "
       "takes the UAV from COVER",
       is_zero},
  };
}

std::vector<ParameterRule> ardupilot_rules() {
  return {
      {{"ATC_ANGLE_BOOST"},
       ParameterWeight::Blocking,
       "0",
       "ArduPilot multiplies the thrust by 1/cos(tilt); COVER's thrust is already along the "
       "body axis, so it would be compensated twice",
       is_zero},
      {{"GUID_OPTIONS"},
       ParameterWeight::Blocking,
       "bit 3 (8) set",
       "without it ArduPilot reads SET_ATTITUDE_TARGET's thrust as a climb rate",
       thrust_is_thrust},
      {{"GUID_TIMEOUT"},
       ParameterWeight::Advisory,
       "> 0 and <= 3 s",
       "ArduPilot's own setpoint-loss delay: if the bridge dies it levels and holds "
       "altitude after it, until the GCS failsafe (FS_GCS_ENABLE) lands it",
       guided_timeout_short},
      {{"FS_THR_ENABLE"},
       ParameterWeight::Advisory,
       "0 without an RC receiver",
       "with it set and no RC, arming fails (\"RC not found\") and the radio failsafe fires",
       is_zero},
      {{"MOT_THST_HOVER"},
       ParameterWeight::Info,
       "any (the vehicle's hover throttle)",
       "the hover thrust ArduPilot learned; the bridge's estimate can start from it",
       nullptr},
      {{"DISARM_DELAY"},
       ParameterWeight::Info,
       "any (0: never)",
       "ArduPilot disarms this long after arming while landed at zero throttle: arm within "
       "it of the task's start",
       nullptr},
      {{"FS_GCS_ENABLE"},
       ParameterWeight::Advisory,
       "5 (Land)",
       "what ArduPilot does when the HEARTBEATs of MAV_GCS_SYSID stop: with the bridge's "
       "watched, it lands when the bridge dies; without (0), it hovers level after "
       "GUID_TIMEOUT indefinitely, drifting without a position",
       lands},
      {{"FS_GCS_TIMEOUT"},
       ParameterWeight::Advisory,
       "> 0 and <= 5 s",
       "how long after the watched HEARTBEAT stops ArduPilot lands (GCS failsafe); until "
       "then it flies the last setpoint for GUID_TIMEOUT, then hovers level and drifts",
       gcs_timeout_short},
      {{"MAV_GCS_SYSID", "SYSID_MYGCS"},
       ParameterWeight::Advisory,
       "the bridge's own system id (the vehicle's)",
       "the system whose HEARTBEATs ArduPilot's GCS failsafe watches (MAV_GCS_SYSID from "
       "ArduPilot 4.7, SYSID_MYGCS before): the bridge's makes its death a failsafe; a "
       "ground station at another id still commands, but its RC overrides are ignored",
       nullptr,
       watches_the_bridge},
      {{"MAV_SYSID", "SYSID_THISMAV"},
       ParameterWeight::Info,
       "any (the system id)",
       "the autopilot's MAVLink system id (MAV_SYSID from ArduPilot 4.7, SYSID_THISMAV "
       "before)",
       nullptr},
  };
}

}  // namespace

std::vector<ParameterRule> parameter_rules(Autopilot kind) {
  return kind == Autopilot::Px4 ? px4_rules() : ardupilot_rules();
}

}  // namespace cover::fc_bridge
