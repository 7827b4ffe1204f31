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
// "px4"): the commander's events and the mode requirement checks, texts as PX4 writes them.
const EventRow kEvents[] = {
    {"check_armable_configuration", "Vehicle is in safety configuration", {A::U32, A::U8}},
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
    {"check_system_arm_auth_failed", "Arm authorization denied", {A::U32, A::U8}},
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
