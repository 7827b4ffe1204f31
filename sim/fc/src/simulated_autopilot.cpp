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

constexpr std::uint8_t kSeverityCritical = 2;
constexpr std::uint8_t kSeverityWarning = 4;
constexpr std::uint8_t kSeverityInfo = 6;

bool finite(const mavlink::SetAttitudeTarget& s) {
  return std::isfinite(s.body_roll_rate) && std::isfinite(s.body_pitch_rate) &&
         std::isfinite(s.body_yaw_rate) && std::isfinite(s.thrust);
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

bool SimulatedAutopilot::Stream::due(double now_s) {
  // A small tolerance: the simulated time is a sum of control periods.
  if (now_s + 1e-9 < next_due_s) return false;
  next_due_s += period_s;
  if (next_due_s <= now_s) next_due_s = now_s + period_s;  // fell behind: no burst
  return true;
}

SimulatedAutopilot::SimulatedAutopilot(AutopilotProfile profile, std::uint8_t system_id,
                                       const SimFcParams& params)
    : profile_(profile),
      params_(params),
      encoder_(system_id, mavlink::mav_comp::kAutopilot1),
      battery_(params.battery),
      heartbeat_stream_{1.0 / params.heartbeat_rate_hz, 0.0},
      attitude_stream_{1.0 / params.attitude_rate_hz, 0.0},
      imu_stream_{1.0 / params.highres_imu_rate_hz, 0.0},
      target_stream_{1.0 / params.attitude_target_rate_hz, 0.0},
      ext_state_stream_{1.0 / params.extended_sys_state_rate_hz, 0.0},
      status_stream_{1.0 / params.sys_status_rate_hz, 0.0} {}

FrameResponse SimulatedAutopilot::on_frame(const mavlink::Frame& frame, double now_s) {
  last_now_s_ = now_s;
  FrameResponse response;
  // Our own frames, echoed. A companion is often another component of our system (191).
  if (frame.system_id == system_id() && frame.component_id == encoder_.component_id()) {
    return response;
  }
  if (const auto setpoint = mavlink::decode<mavlink::SetAttitudeTarget>(frame)) {
    handle_setpoint(frame, *setpoint, now_s, response);
  } else if (const auto command = mavlink::decode<mavlink::CommandLong>(frame)) {
    handle_command(frame, *command, now_s);
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
  // A stream is unbroken while setpoints come faster than the minimum rate.
  if (!setpoint_ || now_s - setpoint_->received_s > 1.0 / params_.offboard_stream_min_rate_hz) {
    stream_start_s_ = now_s;
  }
  setpoint_ = Setpoint{setpoint, now_s};
  ++setpoints_accepted_;
  if (guided_levelled_since_s_) {
    guided_levelled_since_s_.reset();
    in_failsafe_ = false;
    event(AutopilotEvent::Kind::Failsafe, now_s, "GUIDED: setpoints again, following them",
          kSeverityInfo);
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

bool SimulatedAutopilot::setpoint_fresh(double now_s) const {
  return setpoint_age_s(now_s) <= 1.0 / params_.offboard_stream_min_rate_hz;
}

bool SimulatedAutopilot::stream_established(double now_s) const {
  return setpoint_fresh(now_s) && now_s - stream_start_s_ + 1e-9 >= params_.offboard_stream_min_s;
}

AutopilotStep SimulatedAutopilot::step(double now_s, const World& world) {
  last_now_s_ = now_s;
  resting_ = world.state().uav_contact.resting;
  if (armed_ && mode_ == FlightMode::Land && resting_) disarm(now_s, "landed");
  check_offboard_loss(now_s);
  AutopilotStep out;
  out.plant_command = plant_command(world);
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
  if (profile_ == AutopilotProfile::Px4) {
    if (age_s <= params_.com_of_loss_t_s) return;
    in_failsafe_ = true;
    event(AutopilotEvent::Kind::Failsafe, now_s, "Failsafe: offboard lost, descending",
          kSeverityCritical);
    set_mode(FlightMode::Land, now_s, "failsafe");
    return;
  }
  if (!guided_levelled_since_s_ && age_s > params_.guid_timeout_s) {
    guided_levelled_since_s_ = now_s;
    in_failsafe_ = true;
    event(AutopilotEvent::Kind::Failsafe, now_s, "GUIDED: setpoint timeout, levelling",
          kSeverityCritical);
  }
  if (guided_levelled_since_s_ && now_s - *guided_levelled_since_s_ >= params_.guid_level_hold_s) {
    event(AutopilotEvent::Kind::Failsafe, now_s, "Failsafe: no setpoints, landing",
          kSeverityCritical);
    set_mode(FlightMode::Land, now_s, "failsafe");
  }
}

QuadrotorCommand SimulatedAutopilot::plant_command(const World& world) {
  if (!armed_) return QuadrotorCommand{};
  switch (mode_) {
    case FlightMode::Manual:
    case FlightMode::Position:
      return hold_command(world);
    case FlightMode::Land:
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
  QuadrotorCommand command;
  command.thrust_m_s2 =
      std::clamp(static_cast<double>(s.thrust), 0.0, 1.0) * world.params().uav.max_thrust_m_s2;
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

void SimulatedAutopilot::set_mode(FlightMode mode, double now_s, const std::string& why) {
  if (mode == mode_) return;
  mode_ = mode;
  hold_height_m_.reset();
  guided_levelled_since_s_.reset();
  if (mode != FlightMode::Land) in_failsafe_ = false;
  event(AutopilotEvent::Kind::Mode, now_s, std::string("Mode ") + mode_name() + " (" + why + ")",
        kSeverityInfo);
}

void SimulatedAutopilot::arm(double now_s, const std::string& why) {
  armed_ = true;
  hold_height_m_.reset();
  event(AutopilotEvent::Kind::Arming, now_s, "Armed (" + why + ")", kSeverityInfo);
}

void SimulatedAutopilot::disarm(double now_s, const std::string& why) {
  armed_ = false;
  event(AutopilotEvent::Kind::Arming, now_s, "Disarmed (" + why + ")", kSeverityInfo);
}

void SimulatedAutopilot::event(AutopilotEvent::Kind kind, double now_s, const std::string& text,
                               std::uint8_t severity) {
  events_.push_back({kind, now_s, text});
  mavlink::StatusText status;
  status.severity = severity;
  status.set_text(text);
  queue(status);
}

void SimulatedAutopilot::warn_limited(const std::string& text, double now_s) {
  auto it = warned_at_s_.find(text);
  if (it != warned_at_s_.end() && now_s - it->second < 1.0) return;
  warned_at_s_[text] = now_s;
  event(AutopilotEvent::Kind::Refusal, now_s, text, kSeverityWarning);
}

}  // namespace cover::sim::fc
