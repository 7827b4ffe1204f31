#include "cover/sim/fc/simulated_autopilot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cover/mavlink/protocol.hpp"
#include "cover/sim/fc/frame_conventions.hpp"
#include "cover/sim/fc/levelled_flight.hpp"

namespace cover::sim::fc {

namespace {

namespace typemask = mavlink::attitude_target_typemask;

constexpr std::uint8_t kSeverityWarning = 4;  // MAV_SEVERITY_WARNING
// ArduCopter's LAND_WITH_DELAY_MS: a failsafe's LAND holds its height this long first.
constexpr double kLandWithDelay_s = 4.0;

bool finite(const mavlink::SetAttitudeTarget& s) {
  return std::isfinite(s.body_roll_rate) && std::isfinite(s.body_pitch_rate) &&
         std::isfinite(s.body_yaw_rate) && std::isfinite(s.thrust);
}

// ArduPilot's angle boost (AC_AttitudeControl_Multi::get_throttle_boosted): the throttle
// divided by the cosine of the tilt (at least 0.1), faded out towards inverted flight.
double angle_boost(const World& world) {
  const Eigen::Quaterniond q = world.state().uav.attitude.eigen();
  const double cos_tilt = (q * Eigen::Vector3d::UnitZ()).z();
  const double inverted_factor = std::clamp(10.0 * cos_tilt, 0.0, 1.0);
  return inverted_factor / std::clamp(cos_tilt, 0.1, 1.0);
}

}  // namespace

const char* to_string(AutopilotEvent::Kind kind) {
  switch (kind) {
    case AutopilotEvent::Kind::Mode:
      return "mode";
    case AutopilotEvent::Kind::Arming:
      return "arming";
    case AutopilotEvent::Kind::Failsafe:
      return "failsafe";
    case AutopilotEvent::Kind::Refusal:
      return "refusal";
    case AutopilotEvent::Kind::Payload:
      return "payload";
  }
  return "unknown";
}

SimulatedAutopilot::SimulatedAutopilot(Autopilot profile, std::uint8_t system_id,
                                       const SimFcParams& params, StepClosing closing)
    : profile_(profile),
      params_(params),
      closing_(closing),
      encoder_(system_id, mavlink::mav_comp::kAutopilot1),
      battery_(params.battery),
      streams_(profile, profile == Autopilot::Px4 ? params.px4.streams : params.ardupilot.streams),
      parameters_(profile, params, system_id),
      auto_disarm_(profile, params),
      mode_(start_mode(profile)),
      mode_before_land_(start_mode(profile)) {}

FrameResponse SimulatedAutopilot::on_frame(const mavlink::Frame& frame, double now_s) {
  last_now_s_ = now_s;
  FrameResponse response;
  // Our own frames, echoed. A companion is often another component of our system (191).
  if (frame.system_id == system_id() && frame.component_id == encoder_.component_id()) {
    return response;
  }
  link_active_ = true;
  if (frame.message_id == mavlink::Heartbeat::kId &&
      frame.system_id == watched_gcs_sysid(params_.ardupilot, system_id())) {
    gcs_seen_s_ = now_s;
  }
  if (const auto setpoint = mavlink::decode<mavlink::SetAttitudeTarget>(frame)) {
    handle_setpoint(frame, *setpoint, now_s, response);
  } else if (const auto command = mavlink::decode<mavlink::CommandLong>(frame)) {
    handle_command(frame, *command, now_s);
  } else if (const auto request = mavlink::decode<mavlink::ParamRequestRead>(frame)) {
    handle_param_request(frame, *request);
  } else if (const auto timesync = mavlink::decode<mavlink::Timesync>(frame)) {
    handle_timesync(*timesync, now_s);
  }
  response.frames.swap(outbox_);
  outbox_.clear();
  return response;
}

void SimulatedAutopilot::handle_setpoint(const mavlink::Frame& frame,
                                         const mavlink::SetAttitudeTarget& setpoint, double now_s,
                                         FrameResponse& response) {
  if (!setpoint_usable(frame, setpoint, now_s)) {
    ++setpoints_ignored_;
    return;
  }
  companion_ = std::make_pair(frame.system_id, frame.component_id);
  setpoint_ = Setpoint{setpoint, now_s};
  ++setpoints_accepted_;
  if (guided_levelled_since_s_) {
    guided_levelled_since_s_.reset();
    in_failsafe_ = false;
    log_event(AutopilotEvent::Kind::Failsafe, now_s, "GUIDED: setpoints again, following them");
  }
  response.setpoint_accepted = true;
  response.setpoint_time_boot_ms = setpoint.time_boot_ms;
}

bool SimulatedAutopilot::setpoint_usable(const mavlink::Frame& frame,
                                         const mavlink::SetAttitudeTarget& setpoint, double now_s) {
  if (setpoint.target_system != system_id()) {
    warn_limited("Setpoint for system " + std::to_string(setpoint.target_system) +
                     " ignored: this is system " + std::to_string(system_id()),
                 now_s);
    return false;
  }
  if (companion_ && *companion_ != std::make_pair(frame.system_id, frame.component_id)) {
    warn_limited("Setpoint from " + std::to_string(frame.system_id) + "/" +
                     std::to_string(frame.component_id) +
                     " ignored: " + std::to_string(companion_->first) + "/" +
                     std::to_string(companion_->second) + " is the companion",
                 now_s);
    return false;
  }
  const std::uint8_t rates_ignored =
      typemask::kIgnoreBodyRollRate | typemask::kIgnoreBodyPitchRate | typemask::kIgnoreBodyYawRate;
  if ((setpoint.type_mask & typemask::kIgnoreAttitude) == 0 ||
      (setpoint.type_mask & (typemask::kIgnoreThrust | rates_ignored)) != 0) {
    warn_limited(
        "Setpoint type_mask " + std::to_string(setpoint.type_mask) + " ignored: rates+thrust only",
        now_s);
    return false;
  }
  if (!finite(setpoint)) {
    warn_limited("Setpoint ignored: not finite", now_s);
    return false;
  }
  return true;
}

void SimulatedAutopilot::handle_timesync(const mavlink::Timesync& request, double now_s) {
  if (request.tc1 != 0) return;  // an answer to a request of ours (we send none)
  mavlink::Timesync reply;
  reply.tc1 = std::llround(now_s * 1e9);
  reply.ts1 = request.ts1;
  queue(reply);
}

double SimulatedAutopilot::setpoint_age_s(double now_s) const {
  return setpoint_ ? now_s - setpoint_->received_s : std::numeric_limits<double>::infinity();
}

// PX4's offboard signal: an offboard_control_mode (published by every SET_ATTITUDE_TARGET,
// in any mode) within COM_OF_LOSS_T (HealthAndArmingChecks offboardCheck.cpp).
bool SimulatedAutopilot::offboard_signal(double now_s) const {
  return setpoint_age_s(now_s) <= params_.px4.com_of_loss_t_s;
}

AutopilotStep SimulatedAutopilot::step(double now_s, const World& world) {
  last_now_s_ = now_s;
  resting_ = world.state().uav_contact.resting;
  // ArduPilot's LAND disarms as soon as it touches down; PX4's waits COM_DISARM_LAND.
  if (armed_ && mode_ == FlightMode::Land && resting_ && profile_ == Autopilot::ArduPilot) {
    disarm(now_s, "landed", 0);
  }
  check_offboard_loss(now_s);
  check_gcs_failsafe(now_s);
  AutopilotStep out;
  out.plant_command = plant_command(world);
  check_auto_disarm(now_s);
  if (!armed_) out.plant_command = QuadrotorCommand{};
  report_alignment(now_s);
  const double hover = world.hover_thrust_command_m_s2();
  battery_.update(last_step_s_ ? now_s - *last_step_s_ : 0.0,
                  hover > 0.0 ? out.plant_command.thrust_m_s2 / hover : 0.0);
  last_step_s_ = now_s;
  out.release_payload = release_requested_;
  release_requested_ = false;
  queue_streams(now_s, world, out.plant_command);
  out.frames.swap(outbox_);
  outbox_.clear();
  return out;
}

void SimulatedAutopilot::check_offboard_loss(double now_s) {
  if (!armed_ || mode_ != FlightMode::Offboard) return;
  const double age_s = setpoint_age_s(now_s);
  if (profile_ == Autopilot::Px4) {
    if (age_s <= params_.px4.com_of_loss_t_s) return;
    in_failsafe_ = true;
    log_event(AutopilotEvent::Kind::Failsafe, now_s, "Failsafe: offboard lost, descending");
    report(Px4Event("commander_failsafe_enter_generic", Px4EventLevel::Critical)
               .arg(std::uint32_t{0})
               .arg(kPx4FailsafeDescend),
           now_s);
    set_mode(FlightMode::Land, now_s, "failsafe");
    return;
  }
  // ArduPilot levels and holds silently and indefinitely (mode_guided.cpp): its GCS failsafe
  // or, on the ground, DISARM_DELAY ends it.
  if (!guided_levelled_since_s_ && age_s > params_.ardupilot.guid_timeout_s) {
    guided_levelled_since_s_ = now_s;
    in_failsafe_ = true;
    log_event(AutopilotEvent::Kind::Failsafe, now_s, "GUIDED: setpoint timeout, levelling");
  }
}

// ArduCopter's failsafe_gcs_check and failsafe_gcs_on_event (events.cpp): armed, the
// watched HEARTBEAT silent for longer than FS_GCS_TIMEOUT after one has come: on the
// ground a disarm, in the air LAND "with pause". Its return clears the failsafe, not LAND.
void SimulatedAutopilot::check_gcs_failsafe(double now_s) {
  const ArduPilotParams& a = params_.ardupilot;
  if (profile_ != Autopilot::ArduPilot || a.fs_gcs_enable == 0 || !gcs_seen_s_) return;
  const bool silent = now_s - *gcs_seen_s_ > a.fs_gcs_timeout_s;
  if (!silent) {
    if (gcs_failsafe_) say(kSeverityWarning, "GCS Failsafe Cleared");
    gcs_failsafe_ = false;
    return;
  }
  if (gcs_failsafe_ || !armed_) return;
  gcs_failsafe_ = true;
  if (resting_) {
    say(kSeverityWarning, "GCS Failsafe - Disarming");
    disarm(now_s, "GCS failsafe", 0);
    return;
  }
  say(kSeverityWarning, "GCS Failsafe");
  log_event(AutopilotEvent::Kind::Failsafe, now_s, "GCS failsafe: landing");
  const bool already_landing = mode_ == FlightMode::Land;
  set_mode(FlightMode::Land, now_s, "GCS failsafe");
  in_failsafe_ = true;
  if (!already_landing) land_descent_from_s_ = now_s + kLandWithDelay_s;
}

// The land detector (the plant's contact) and the firmware's auto-disarm. ArduPilot's
// throttle is at zero unless COVER's setpoint asks for thrust: without RC its pilot
// throttle is zero in every mode, and GUIDED_NOGPS without a setpoint (or levelled after
// GUID_TIMEOUT) flies no thrust of COVER's.
void SimulatedAutopilot::check_auto_disarm(double now_s) {
  if (!armed_) return;
  const bool flying_setpoint = mode_ == FlightMode::Offboard && setpoint_ &&
                               !guided_levelled_since_s_ && setpoint_->message.thrust > 0.0F;
  const AutoDisarmStep s = auto_disarm_.step(now_s, resting_, !flying_setpoint);
  if (s.took_off) report(Px4Event("commander_takeoff_detected", Px4EventLevel::Info), now_s);
  if (s.landed) report(Px4Event("commander_landing_detected", Px4EventLevel::Info), now_s);
  if (!s.disarm) return;
  switch (*s.disarm) {
    case AutoDisarmCause::Px4Preflight:
      disarm(now_s, "auto: preflight inaction", px4_arm_reason::kPreflightInaction);
      break;
    case AutoDisarmCause::Px4Landed:
      disarm(now_s, "auto: landed", px4_arm_reason::kLanding);
      break;
    case AutoDisarmCause::ArduPilotDelay:
      disarm(now_s, "auto: DISARM_DELAY", 0);
      break;
  }
}

QuadrotorCommand SimulatedAutopilot::plant_command(const World& world) {
  if (!armed_) return QuadrotorCommand{};
  switch (mode_) {
    case FlightMode::Hold:
    case FlightMode::Manual:
    case FlightMode::Position:
      return hold_command(world);
    case FlightMode::Land:
      if (land_descent_from_s_ && last_now_s_ < *land_descent_from_s_) return hold_command(world);
      return levelled_vertical_speed_command(world, -params_.land_speed_m_s);
    case FlightMode::Offboard:
      if (guided_levelled_since_s_ || !setpoint_) return hold_command(world);
      return setpoint_command(world);
  }
  return QuadrotorCommand{};
}

QuadrotorCommand SimulatedAutopilot::hold_command(const World& world) {
  if (!hold_height_m_) hold_height_m_ = world.state().uav.position_m.z;
  return levelled_height_hold_command(world, *hold_height_m_);
}

// The last setpoint, held until it is stale (the failsafe above decides when).
QuadrotorCommand SimulatedAutopilot::setpoint_command(const World& world) const {
  const mavlink::SetAttitudeTarget& s = setpoint_->message;
  double throttle = std::clamp(static_cast<double>(s.thrust), 0.0, 1.0);
  if (profile_ == Autopilot::ArduPilot && params_.ardupilot.atc_angle_boost != 0) {
    throttle = std::clamp(throttle * angle_boost(world), 0.0, 1.0);
  }
  QuadrotorCommand command;
  command.thrust_m_s2 = throttle * world.params().uav.max_thrust_m_s2;
  command.body_rate_rad_s =
      Vec3(frd_to_flu(Eigen::Vector3d(s.body_roll_rate, s.body_pitch_rate, s.body_yaw_rate)));
  return command;
}

void SimulatedAutopilot::inject_mode_switch(FlightMode mode) {
  set_mode(mode, last_now_s_, "RC switch");
}

void SimulatedAutopilot::stop_heartbeats() {
  heartbeats_stopped_ = true;
}

std::optional<mavlink::EncodedFrame> SimulatedAutopilot::heartbeat_frame() {
  if (heartbeats_stopped_) return std::nullopt;
  return encoder_.encode(heartbeat());
}

}  // namespace cover::sim::fc
