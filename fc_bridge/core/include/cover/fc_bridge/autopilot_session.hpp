#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cover/fc_bridge/autopilot_profile.hpp"
#include "cover/mavlink/frame.hpp"

namespace cover::fc_bridge {

// MAV_LANDED_STATE, from EXTENDED_SYS_STATE.
enum class LandedState { Undefined, OnGround, InAir, Takeoff, Landing };
const char* to_string(LandedState state);

// What the autopilot says about itself. Learns which system is the autopilot from the
// first HEARTBEAT of a component 1 whose autopilot is not MAV_AUTOPILOT_INVALID (a ground
// station or a companion says 8), then hears only that system's component 1. The link is
// up while its HEARTBEATs come within `heartbeat_timeout_s`: only HEARTBEATs count, a
// stream of other frames from a hung autopilot task does not.
class AutopilotSession {
 public:
  AutopilotSession(AutopilotProfile profile, double heartbeat_timeout_s);

  // Takes a frame; false when it is not the autopilot's (another system, a ground station,
  // anything before the autopilot's first HEARTBEAT), which the caller then ignores.
  bool accept(const mavlink::Frame& frame, double now_s);

  bool known() const { return system_id_ != 0; }
  std::uint8_t system_id() const { return system_id_; }  // 0: not heard yet
  std::uint8_t component_id() const { return component_id_; }
  std::uint8_t reported_autopilot() const { return reported_autopilot_; }  // MAV_AUTOPILOT
  bool link_ok(double now_s) const;
  double last_heartbeat_s() const { return last_heartbeat_s_; }

  bool armed() const { return armed_; }
  FcMode mode() const { return mode_; }
  const std::string& mode_name() const { return mode_name_; }
  std::uint32_t custom_mode() const { return custom_mode_; }
  LandedState landed_state() const { return landed_state_; }
  double battery_voltage_v() const { return battery_voltage_v_; }  // < 0: unknown
  double battery_remaining() const { return battery_remaining_; }  // 0..1, < 0: unknown
  const std::string& status_text() const { return status_text_; }
  std::uint8_t status_severity() const { return status_severity_; }
  std::uint64_t status_text_count() const { return status_text_count_; }
  // A text the autopilot sent another way than STATUSTEXT (PX4's EVENTs), kept as its last.
  void report_text(std::string text, std::uint8_t severity);
  // The autopilot accepted our COMPONENT_ARM_DISARM at `now_s`. PX4 and ArduPilot change
  // their arming state before they answer, so the answer is the new state, up to a HEARTBEAT
  // period (1 s) before a HEARTBEAT shows it. A HEARTBEAT that still shows the old state
  // within kAckedStateHold_s of the answer was sent before the change took effect (PX4
  // publishes its vehicle_status after the ACK) and does not undo it; a later one does.
  void on_arming_accepted(bool armed, double now_s);
  // The same for an accepted DO_SET_MODE (`base_mode` and `custom_mode` as a HEARTBEAT would
  // carry them): the mode asked for, held against older HEARTBEATs as the arming is.
  void on_mode_accepted(std::uint8_t base_mode, std::uint32_t custom_mode, double now_s);
  static constexpr double kAckedStateHold_s = 0.5;

 private:
  bool learn(const mavlink::Frame& frame);
  void on_heartbeat(const mavlink::Frame& frame, double now_s);
  void on_sys_status(const mavlink::Frame& frame);
  void on_battery_status(const mavlink::Frame& frame);
  void on_extended_sys_state(const mavlink::Frame& frame);
  void on_status_text(const mavlink::Frame& frame);

  AutopilotProfile profile_;
  double heartbeat_timeout_s_;
  std::uint8_t system_id_ = 0;
  std::uint8_t component_id_ = 0;
  std::uint8_t reported_autopilot_ = 0;
  double last_heartbeat_s_ = -1.0;
  bool armed_ = false;
  std::optional<bool> acked_armed_;  // an accepted arm / disarm no HEARTBEAT has shown yet
  double acked_armed_s_ = 0.0;
  std::optional<std::uint32_t> acked_mode_;  // an accepted DO_SET_MODE no HEARTBEAT has shown
  double acked_mode_s_ = 0.0;
  FcMode mode_ = FcMode::Unknown;
  std::string mode_name_ = "unknown";
  std::uint8_t base_mode_ = 0;
  std::uint32_t custom_mode_ = 0;
  LandedState landed_state_ = LandedState::Undefined;
  double battery_voltage_v_ = -1.0;
  double battery_remaining_ = -1.0;
  std::string status_text_;
  std::uint8_t status_severity_ = 6;
  std::uint64_t status_text_count_ = 0;
};

}  // namespace cover::fc_bridge
