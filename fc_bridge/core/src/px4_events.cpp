#include "cover/fc_bridge/px4_events.hpp"

#include <array>
#include <cstdio>
#include <cstring>
#include <initializer_list>

namespace cover::fc_bridge {
namespace {

// The type of an event argument, as PX4's metadata declares it; enums carry their names.
enum class A {
  U8,
  U16,
  U32,
  I16,
  I32,
  Float,
  ArmDisarmReason,
  FailsafeAction,
  FailsafeCause,
  NavigationMode
};

struct EventRow {
  const char* name;
  const char* message;  // "{n}" (with an optional ":format") is argument n, from 1
  std::initializer_list<A> arguments;
};

// From PX4's event metadata (all_events.json of the PX4 build at 02e73e3b, component
// "px4"): the commander's events and its arming and health checks (the reasons behind an
// arming refusal), texts as PX4 writes them. Enum arguments other than the four rendered by
// name are shown as their numbers.
const EventRow kEvents[] = {
    {"check_accel_missing", "Accelerometer sensor {3} missing", {A::U32, A::U8, A::U8}},
    {"check_accel_no_data", "No valid data from Accelerometer {3}", {A::U32, A::U8, A::U8}},
    {"check_accel_not_calibrated", "Accelerometer {3} uncalibrated", {A::U32, A::U8, A::U8}},
    {"check_airspeed_invalid", "Airspeed invalid", {A::U32, A::U8}},
    {"check_airspeed_no_data", "No airspeed data", {A::U32, A::U8}},
    {"check_airspeed_too_high", "Airspeed too high", {A::U32, A::U8, A::Float, A::Float}},
    {"check_armable_configuration", "Vehicle is in safety configuration", {A::U32, A::U8}},
    {"check_avionics_power_high",
     "Avionics Power high: {3:.2} Volt",
     {A::U32, A::U8, A::Float, A::Float}},
    {"check_avionics_power_low",
     "Avionics Power low: {3:.2} Volt",
     {A::U32, A::U8, A::Float, A::Float}},
    {"check_avionics_power_missing", "Power module not connected", {A::U32, A::U8}},
    {"check_avionics_power_redundancy", "Power redundancy not met", {A::U32, A::U8, A::U8, A::U8}},
    {"check_baro_missing", "Barometer {3} missing", {A::U32, A::U8, A::U8}},
    {"check_baro_no_data", "No valid data from barometer {3}", {A::U32, A::U8, A::U8}},
    {"check_battery_critical", "Critical battery", {A::U32, A::U8}},
    {"check_battery_disconnected", "Battery {3} disconnected", {A::U32, A::U8, A::U8}},
    {"check_battery_emergency", "Emergency battery level", {A::U32, A::U8}},
    {"check_battery_fault", "Battery {3}: {4}. {5}", {A::U32, A::U8, A::U8, A::U8, A::U8}},
    {"check_battery_low", "Low battery", {A::U32, A::U8}},
    {"check_battery_missing", "Battery {3} missing", {A::U32, A::U8, A::U8}},
    {"check_battery_rem_flight_time_low", "Remaining flight time low", {A::U32, A::U8}},
    {"check_battery_unhealthy", "Battery unhealthy", {A::U32, A::U8}},
    {"check_cpuload_too_high", "CPU load too high: {3:.1}%", {A::U32, A::U8, A::Float}},
    {"check_distance_sensor_invalid",
     "No valid data from distance sensor {3}",
     {A::U32, A::U8, A::U8}},
    {"check_distance_sensor_missing", "Distance sensor {3} missing", {A::U32, A::U8, A::U8}},
    {"check_escs_fault", "ESC {3}: {4}", {A::U32, A::U8, A::U8, A::U8, A::U8}},
    {"check_escs_offline", "ESC {3} offline", {A::U32, A::U8, A::U8}},
    {"check_escs_telem_missing", "ESC telemetry missing", {A::U32, A::U8}},
    {"check_estimator_gnss_fault", "GNSS heading not reliable", {A::U32, A::U8}},
    {"check_estimator_gps_fix_too_low", "GPS fix too low", {A::U32, A::U8}},
    {"check_estimator_gps_generic", "Poor GPS Quality", {A::U32, A::U8}},
    {"check_estimator_gps_hor_pos_drift_too_high",
     "GPS Horizontal Position Drift too high",
     {A::U32, A::U8}},
    {"check_estimator_gps_hor_pos_err_too_high",
     "GPS Horizontal Position Error too high",
     {A::U32, A::U8}},
    {"check_estimator_gps_hor_speed_drift_too_high",
     "GPS Horizontal Speed Drift too high",
     {A::U32, A::U8}},
    {"check_estimator_gps_jammed", "GPS signal jammed", {A::U32, A::U8}},
    {"check_estimator_gps_jamming_critical", "GPS jamming detected", {A::U32, A::U8}},
    {"check_estimator_gps_not_fusing", "Estimator not using GPS", {A::U32, A::U8}},
    {"check_estimator_gps_num_sats_too_low", "Not enough GPS Satellites", {A::U32, A::U8}},
    {"check_estimator_gps_pdop_too_high", "GPS PDOP too high", {A::U32, A::U8}},
    {"check_estimator_gps_speed_acc_too_low", "GPS Speed Accuracy too low", {A::U32, A::U8}},
    {"check_estimator_gps_spoofed", "GPS signal spoofed", {A::U32, A::U8}},
    {"check_estimator_gps_vert_pos_drift_too_high",
     "GPS Vertical Position Drift too high",
     {A::U32, A::U8}},
    {"check_estimator_gps_vert_pos_err_too_high",
     "GPS Vertical Position Error too high",
     {A::U32, A::U8}},
    {"check_estimator_gps_vert_speed_drift_too_high",
     "GPS Vertical Speed Drift too high",
     {A::U32, A::U8}},
    {"check_estimator_heading_not_stable", "Heading estimate not stable", {A::U32, A::U8}},
    {"check_estimator_hgt_not_stable", "Height estimate not stable", {A::U32, A::U8}},
    {"check_estimator_high_accel_bias",
     "High Accelerometer Bias",
     {A::U32, A::U8, A::U8, A::Float, A::Float, A::Float}},
    {"check_estimator_high_gyro_bias",
     "High Gyro Bias",
     {A::U32, A::U8, A::U8, A::Float, A::Float, A::Float}},
    {"check_estimator_hor_pos_not_stable", "Horizontal position unstable", {A::U32, A::U8}},
    {"check_estimator_hor_vel_not_stable", "Horizontal velocity unstable", {A::U32, A::U8}},
    {"check_estimator_low_position_accuracy",
     "Position estimate has low accuracy",
     {A::U32, A::U8}},
    {"check_estimator_mag_fault", "Stopping compass use", {A::U32, A::U8}},
    {"check_estimator_mag_interference",
     "Strong magnetic interference",
     {A::U32, A::U8, A::Float, A::Float, A::Float, A::Float}},
    {"check_estimator_missing_data", "Waiting for estimator to initialize", {A::U32, A::U8}},
    {"check_estimator_vert_vel_not_stable", "Vertical velocity unstable", {A::U32, A::U8}},
    {"check_external_modes_unavailable", "Mode is not registered", {A::U32, A::U8}},
    {"check_external_modes_unresponsive", "Mode is unresponsive", {A::U32, A::U8}},
    {"check_failure_detector_alt", "Altitude failure detected", {A::U32, A::U8}},
    {"check_failure_detector_arm_esc", "ESC failure", {A::U32, A::U8}},
    {"check_failure_detector_ext", "Failure triggered by external system", {A::U32, A::U8}},
    {"check_failure_detector_imbalanced_prop", "Imbalanced propeller detected", {A::U32, A::U8}},
    {"check_failure_detector_motor", "Motor failure detected", {A::U32, A::U8}},
    {"check_failure_detector_pitch", "Attitude failure detected", {A::U32, A::U8}},
    {"check_failure_detector_roll", "Attitude failure detected", {A::U32, A::U8}},
    {"check_flight_time_limit", "Maximum flight time reached", {A::U32, A::U8}},
    {"check_gf_no_home", "Geofence RTL requires valid home", {A::U32, A::U8}},
    {"check_gf_violation_custom_gf",
     "Geofence violation: approaching or outside geofence",
     {A::U32, A::U8}},
    {"check_gf_violation_max_alt",
     "Geofence violation: exceeding maximum altitude above Home",
     {A::U32, A::U8}},
    {"check_gf_violation_max_hor_dist",
     "Geofence violation: exceeding maximum distance to Home",
     {A::U32, A::U8}},
    {"check_gyro_missing", "Gyro sensor {3} missing", {A::U32, A::U8, A::U8}},
    {"check_gyro_no_data", "No valid data from Gyro {3}", {A::U32, A::U8, A::U8}},
    {"check_gyro_not_calibrated", "Gyro {3} uncalibrated", {A::U32, A::U8, A::U8}},
    {"check_hardfault_present", "Crash dumps present on SD card", {A::U32, A::U8}},
    {"check_imu_accel_inconsistent",
     "Accel {3} inconsistent",
     {A::U32, A::U8, A::U8, A::Float, A::Float}},
    {"check_imu_gyro_inconsistent",
     "Gyro {3} inconsistent",
     {A::U32, A::U8, A::U8, A::Float, A::Float}},
    {"check_mag_consistency", "Compass inconsistent by {3} degrees", {A::U32, A::U8, A::I16}},
    {"check_mag_fault", "Estimator fault due to Compass {3}", {A::U32, A::U8, A::U8}},
    {"check_mag_missing", "Compass sensor {3} missing", {A::U32, A::U8, A::U8}},
    {"check_mag_no_data", "No valid data from Compass {3}", {A::U32, A::U8, A::U8}},
    {"check_mag_not_calibrated", "Compass {3} uncalibrated", {A::U32, A::U8, A::U8}},
    {"check_mag_sys_has_mag_missing",
     "Found {3} compass (required: {4})",
     {A::U32, A::U8, A::U8, A::U8}},
    {"check_man_control_kill_engaged", "Kill switch engaged", {A::U32, A::U8}},
    {"check_man_control_landing_gear_up",
     "Landing gear switch set in UP position",
     {A::U32, A::U8}},
    {"check_man_control_rtl_engaged", "RTL switch engaged", {A::U32, A::U8}},
    {"check_missing_cpuload", "No CPU and RAM load information", {A::U32, A::U8}},
    {"check_missing_fmu_sdcard", "Missing FMU SD Card", {A::U32, A::U8}},
    {"check_missing_system_power", "System power unavailable", {A::U32, A::U8}},
    {"check_mission_failure", "Mission cannot be completed", {A::U32, A::U8}},
    {"check_modes_angular_velocity", "Angular velocity not valid", {A::U32, A::U8}},
    {"check_modes_attitude", "No valid attitude estimate", {A::U32, A::U8}},
    {"check_modes_cannot_takeoff", "Mode not suitable for arming", {A::U32, A::U8}},
    {"check_modes_global_pos",
     "Navigation error: No valid global position estimate",
     {A::U32, A::U8}},
    {"check_modes_home_position", "Home position not set", {A::U32, A::U8}},
    {"check_modes_local_alt", "Navigation error: No valid altitude estimate", {A::U32, A::U8}},
    {"check_modes_local_pos", "Navigation error: No valid position estimate", {A::U32, A::U8}},
    {"check_modes_manual_control", "No manual control input", {A::U32, A::U8}},
    {"check_modes_mission", "No valid mission available", {A::U32, A::U8}},
    {"check_modes_offboard_signal", "No offboard signal", {A::U32, A::U8}},
    {"check_navigator_failure_hagl", "Waypoint above maximum height", {A::U32, A::U8}},
    {"check_open_drone_id_missing", "Open Drone ID system missing", {A::U32, A::U8}},
    {"check_open_drone_id_unhealthy", "Open Drone ID system not ready", {A::U32, A::U8}},
    {"check_optical_flow_sensor_invalid",
     "No valid data from optical flow sensor",
     {A::U32, A::U8}},
    {"check_optical_sensor_missing", "Optical flow sensor missing", {A::U32, A::U8}},
    {"check_parachute_missing", "Parachute system missing", {A::U32, A::U8}},
    {"check_parachute_unhealthy", "Parachute system not ready", {A::U32, A::U8}},
    {"check_power_oc_hipower", "Overcurrent detected for the hipower 5V supply", {A::U32, A::U8}},
    {"check_power_oc_periph", "Overcurrent detected for the peripheral 5V supply", {A::U32, A::U8}},
    {"check_ram_usage_too_high", "RAM usage too high: {3:.1}%", {A::U32, A::U8, A::Float}},
    {"check_rc_dl_no_dllink", "No connection to the ground control station", {A::U32, A::U8}},
    {"check_rc_max_too_high",
     "RC calibration for channel {3} invalid: MAX greater than {4}",
     {A::U32, A::U8, A::U8, A::U16}},
    {"check_rc_min_too_small",
     "RC calibration for channel {3} invalid: MIN less than {4}",
     {A::U32, A::U8, A::U8, A::U16}},
    {"check_rc_trim_too_high",
     "RC calibration for channel {3} invalid: TRIM greater than MAX ({4} greater than {5})",
     {A::U32, A::U8, A::U8, A::I16, A::I16}},
    {"check_rc_trim_too_small",
     "RC calibration for channel {3} invalid: TRIM less than MIN ({4} less than {5})",
     {A::U32, A::U8, A::U8, A::I16, A::I16}},
    {"check_system_arm_auth_failed", "Arm authorization denied", {A::U32, A::U8}},
    {"check_system_flight_term_active", "Flight termination active", {A::U32, A::U8}},
    {"check_system_no_global_pos", "Global position estimate required", {A::U32, A::U8}},
    {"check_system_no_home_pos", "Home position required", {A::U32, A::U8}},
    {"check_system_safety_button", "Press safety button first", {A::U32, A::U8}},
    {"check_system_usb_connected", "USB connected", {A::U32, A::U8}},
    {"check_system_vtol_in_fw_mode", "Vehicle is not in multicopter mode", {A::U32, A::U8}},
    {"check_system_vtol_in_transition", "Vehicle is in transition state", {A::U32, A::U8}},
    {"check_task_watchdog_present", "Task watchdog dumps present on SD card", {A::U32, A::U8}},
    {"check_traffic_avoidance_missing", "Traffic avoidance system missing", {A::U32, A::U8}},
    {"check_vtol_fixed_wing_system_failure",
     "VTOL fixed-wing system failure detected. Verify reason for failure, and reboot the vehicle "
     "once confirmed safe",
     {A::U32, A::U8}},
    {"check_wind_too_high", "Wind speed is above limit ({3:.1m/s})", {A::U32, A::U8, A::Float}},
    {"commander_airmode_requires_no_arm_gesture",
     "Yaw Airmode requires disabling the stick arm gesture",
     {}},
    {"commander_arm_denied_calibrating", "Arming denied: calibrating", {}},
    {"commander_arm_denied_not_manual", "Arming denied: switch to manual mode first", {}},
    {"commander_arm_denied_resolve_failures",
     "Arming denied: Resolve system health failures first",
     {}},
    {"commander_arm_denied_throttle_center", "Arming denied: throttle above center", {}},
    {"commander_arm_denied_throttle_high", "Arming denied: high throttle", {}},
    {"commander_armed_by", "Armed by {1}", {A::ArmDisarmReason}},
    {"commander_ctrl_high_latency_failed",
     "Control high latency failed! Telemetry unavailable",
     {}},
    {"commander_disarm_denied_not_landed", "Disarming denied: not landed", {}},
    {"commander_disarmed_by", "Disarmed by {1}", {A::ArmDisarmReason}},
    {"commander_dl_regained", "GCS connection regained", {}},
    {"commander_esc_calibration_denied", "ESCs calibration denied", {}},
    {"commander_failsafe_enter",
     "{3}: switching to {2}",
     {A::U32, A::FailsafeAction, A::FailsafeCause}},
    {"commander_failsafe_enter_autopilot_disengaged",
     "Failsafe activated: Autopilot disengaged, switching to {2}",
     {A::U32, A::FailsafeAction}},
    {"commander_failsafe_enter_crit_bat_warn", "Critical battery level, land now", {}},
    {"commander_failsafe_enter_crit_low_bat_warn", "Emergency battery level, land immediately", {}},
    {"commander_failsafe_enter_generic",
     "Failsafe activated: switching to {2}",
     {A::U32, A::FailsafeAction}},
    {"commander_failsafe_enter_generic_hold",
     "Failsafe activated: switching to {2} in {3} seconds",
     {A::U32, A::FailsafeAction, A::U16}},
    {"commander_failsafe_enter_generic_warn", "Failsafe warning:", {A::U32}},
    {"commander_failsafe_enter_hold",
     "{4}: switching to {2} in {3} seconds",
     {A::U32, A::FailsafeAction, A::U16, A::FailsafeCause}},
    {"commander_failsafe_enter_low_bat", "Low battery level, return advised", {}},
    {"commander_failsafe_enter_low_flight_time_warn",
     "Low remaining flight time, return advised",
     {}},
    {"commander_failsafe_enter_warn", "Failsafe warning: {2}", {A::U32, A::FailsafeCause}},
    {"commander_gcs_lost", "Connection to ground control station lost", {}},
    {"commander_high_latency_lost", "High latency data link lost", {}},
    {"commander_kill_sw_disengaged", "Kill disengaged", {}},
    {"commander_kill_sw_engaged", "Kill engaged", {}},
    {"commander_landing_current_pos", "Landing at current position", {}},
    {"commander_landing_detected", "Landing detected", {}},
    {"commander_landing_prec_land", "Landing using precision landing", {}},
    {"commander_load_param_failed", "Error loading settings", {}},
    {"commander_low_bat_shutdown", "Dangerously low battery! Shutting system down", {}},
    {"commander_low_bat_shutdown_failed", "Dangerously low battery! System shut down failed", {}},
    {"commander_max_flight_time_warning_minutes",
     "Approaching max flight time (system will RTL in {1} minutes)",
     {A::I16}},
    {"commander_max_flight_time_warning_seconds",
     "Approaching max flight time (system will RTL in {1} seconds)",
     {A::I16}},
    {"commander_mission_comp_lost", "Connection to mission computer lost", {}},
    {"commander_mission_start_denied_no_mission", "Mission start denied! No valid mission", {}},
    {"commander_mode_fallback_internal",
     "External mode is unresponsive, falling back to internal",
     {}},
    {"commander_modeswitch_not_avail",
     "Switching to mode '{2}' is currently not possible",
     {A::U32, A::NavigationMode}},
    {"commander_onboard_ctrl_regained", "Onboard controller regained", {}},
    {"commander_open_drone_id_regained", "Remote ID system regained", {}},
    {"commander_parachute_regained", "Parachute system regained", {}},
    {"commander_rc_lost", "Manual control lost", {}},
    {"commander_rc_override", "Pilot took over using sticks", {}},
    {"commander_rc_regained", "Manual control regained after {1:.1} s", {A::Float}},
    {"commander_remote_id_lost", "Remote ID system lost", {}},
    {"commander_rtl", "Returning to launch", {}},
    {"commander_save_param_failed", "Error saving settings", {}},
    {"commander_takeoff_detected", "Takeoff detected", {}},
    {"commander_traffic_avoidance_lost", "Traffic avoidance system lost", {}},
    {"commander_traffic_avoidance_regained", "Traffic avoidance system regained", {}},
    {"commander_unsupported_arm_disarm_param", "Unsupported ARM_DISARM param: {1:.3}", {A::Float}},
    {"commander_unsupported_auto_mode", "Unsupported auto mode", {}},
    {"commander_unsupported_base_mode", "Unsupported base mode", {}},
    {"commander_unsupported_main_mode", "Unsupported main mode", {}},
};

const char* arm_disarm_reason(unsigned value) {
  switch (value) {
    case 1:
      return "stick gesture";
    case 2:
      return "RC switch";
    case 3:
      return "internal command";
    case 4:
      return "external command";
    case 5:
      return "mission start";
    case 6:
      return "landing";
    case 7:
      return "preflight inaction";
    case 8:
      return "kill switch";
    case 13:
      return "RC button";
    case 14:
      return "failsafe";
    default:
      return "another reason";
  }
}

const char* failsafe_action(unsigned value) {
  constexpr std::array<const char*, 11> kNames{
      "",    "warning", "Position mode", "Altitude mode", "Stabilized mode", "Hold",
      "RTL", "Land",    "Descend",       "disarm",        "terminate"};
  return value < kNames.size() ? kNames[value] : "another action";
}

const char* failsafe_cause(unsigned value) {
  constexpr std::array<const char*, 7> kNames{"",
                                              "Manual control loss",
                                              "GCS connection loss",
                                              "Low battery level",
                                              "Critical battery level",
                                              "Emergency battery level",
                                              "Remaining flight time low"};
  return value < kNames.size() ? kNames[value] : "another cause";
}

const char* navigation_mode(unsigned value) {
  constexpr std::array<const char*, 25> kNames{"Manual",
                                               "Altitude control",
                                               "Position control",
                                               "Mission",
                                               "Hold",
                                               "RTL",
                                               "Acro",
                                               "Offboard",
                                               "Stabilized",
                                               "Position Slow",
                                               "Takeoff",
                                               "Land",
                                               "Follow Target",
                                               "Precision Landing",
                                               "Orbit",
                                               "Vtol Takeoff",
                                               "External 1",
                                               "External 2",
                                               "External 3",
                                               "External 4",
                                               "External 5",
                                               "External 6",
                                               "External 7",
                                               "External 8",
                                               "Altitude Cruise"};
  return value < kNames.size() ? kNames[value] : "[Unknown]";
}

std::size_t size_of(A type) {
  switch (type) {
    case A::U16:
    case A::I16:
      return 2;
    case A::U32:
    case A::I32:
    case A::Float:
      return 4;
    default:
      return 1;
  }
}

// Argument `type` at `offset` of the packed arguments, in words.
std::string render(A type, const std::uint8_t* bytes) {
  std::uint32_t raw = 0;
  for (std::size_t i = 0; i < size_of(type); ++i)
    raw |= static_cast<std::uint32_t>(bytes[i]) << (8 * i);
  char text[32];
  switch (type) {
    case A::ArmDisarmReason:
      return arm_disarm_reason(raw);
    case A::FailsafeAction:
      return failsafe_action(raw);
    case A::FailsafeCause:
      return failsafe_cause(raw);
    case A::NavigationMode:
      return navigation_mode(raw);
    case A::I16:
      std::snprintf(text, sizeof text, "%d", static_cast<std::int16_t>(raw));
      break;
    case A::I32:
      std::snprintf(text, sizeof text, "%d", static_cast<std::int32_t>(raw));
      break;
    case A::Float: {
      float value = 0.0F;
      std::memcpy(&value, &raw, sizeof value);
      std::snprintf(text, sizeof text, "%.3g", static_cast<double>(value));
      break;
    }
    default:
      std::snprintf(text, sizeof text, "%u", raw);
      break;
  }
  return text;
}

// The message with each "{n[:format]}" replaced by argument n; arguments that do not fit in
// the 40 bytes render as "?".
std::string fill(const EventRow& row, const std::array<std::uint8_t, 40>& arguments) {
  std::array<std::string, 8> values;
  std::size_t offset = 0;
  std::size_t count = 0;
  for (const A type : row.arguments) {
    if (count == values.size()) break;
    const bool fits = offset + size_of(type) <= arguments.size();
    values[count++] = fits ? render(type, arguments.data() + offset) : "?";
    offset += size_of(type);
  }
  std::string out;
  for (const char* c = row.message; *c != '\0'; ++c) {
    const char* close = *c == '{' ? std::strchr(c, '}') : nullptr;
    if (close == nullptr || c[1] < '1' || c[1] > '9') {
      out += *c;
      continue;
    }
    const std::size_t index = static_cast<std::size_t>(c[1] - '1');
    out += index < count ? values[index] : "?";
    c = close;
  }
  return out;
}

}  // namespace

EventText describe_px4_event(const mavlink::Event& event) {
  EventText out;
  const unsigned external_level = event.log_levels & 0x0FU;
  out.level = static_cast<std::uint8_t>(external_level > 7 ? 7 : external_level);
  out.for_operator = external_level <= 7;
  for (const EventRow& row : kEvents) {
    if (px4_event_id(row.name) != event.id) continue;
    out.known = true;
    out.text = fill(row, event.arguments);
    return out;
  }
  char text[96];
  std::snprintf(text, sizeof text, "PX4 event 0x%08x (not in COVER's table: see the PX4 console)",
                static_cast<unsigned>(event.id));
  out.text = text;
  return out;
}

}  // namespace cover::fc_bridge
