#include "cover/fc_bridge/bridge.hpp"

#include <cmath>
#include <cstdio>

#include "cover/fc_bridge/px4_events.hpp"
#include "cover/mavlink/event_messages.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parameter_messages.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/state_messages.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;

// Our HEARTBEAT carries this system id until the autopilot's is known, so that a udpout
// peer hears us first; nothing is targeted at it. Replaced by the autopilot's own id (the
// convention for a companion) as soon as its HEARTBEAT arrives.
constexpr std::uint8_t kProvisionalSystemId = 1;
constexpr double kCompanionHeartbeatPeriod_s = 1.0;
constexpr double kSequencerRetry_s = 1.0;
constexpr double kMilliGToMS2 = 9.80665e-3;  // SCALED_IMU's accelerations are in mG
// A housekeeping pass this much later than the one before means the bridge itself was
// descheduled (the caller ticks at 50 Hz or more): the agent's commands may be waiting in
// its queue, so the command timeout waits for the next pass.
constexpr double kStalledTick_s = 0.06;
// PX4 arms its motors' spool-up (COM_SPOOLUP_TIME, 1 s) before counting COM_DISARM_PRFLT.
constexpr double kPx4SpoolUp_s = 1.0;
// A refused operator command waits this long for the autopilot's reason, and takes the
// texts it sent from this long before the refusal.
constexpr double kReasonWait_s = 0.3;
constexpr double kReasonLookback_s = 0.5;
constexpr std::size_t kRecentTexts = 8;

StreamRates stream_rates(const FcBridgeParams& p) {
  StreamRates r;
  r.highres_imu_hz = p.stream_highres_imu_hz;
  r.extended_sys_state_hz = p.stream_extended_sys_state_hz;
  r.sys_status_hz = p.stream_sys_status_hz;
  r.battery_status_hz = p.stream_battery_status_hz;
  r.estimator_status_hz = p.stream_estimator_status_hz;
  r.attitude_target_hz = p.stream_attitude_target_hz;
  r.local_position_ned_hz = p.stream_local_position_ned_hz;
  return r;
}

HoverThrustEstimatorParams estimator_params(const FcBridgeParams& p) {
  HoverThrustEstimatorParams e;
  e.initial = p.hover_thrust;
  e.min = p.hover_thrust_min;
  e.max = p.hover_thrust_max;
  e.initial_std = p.hover_thrust_initial_std;
  e.noise_per_sqrt_s = p.hover_thrust_noise_per_sqrt_s;
  e.accel_noise_m_s2 = p.accel_noise_m_s2;
  e.gravity_m_s2 = p.gravity_m_s2;
  e.velocity_noise_m_s = p.velocity_noise_m_s;
  e.velocity_model_noise_m_s_per_sqrt_s = p.velocity_model_noise_m_s_per_sqrt_s;
  e.velocity_timeout_s = p.velocity_timeout_s;
  e.velocity_drag_per_s = p.velocity_drag_per_s;
  return e;
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char text[200];
  std::snprintf(text, sizeof(text), fmt, a, b, c);
  return text;
}

const char* autopilot_name(std::uint8_t mav_autopilot) {
  switch (mav_autopilot) {
    case mav::mav_autopilot::kPx4:
      return "PX4";
    case mav::mav_autopilot::kArdupilotMega:
      return "ArduPilot";
    case mav::mav_autopilot::kGeneric:
      return "generic";
    default:
      return "another autopilot";
  }
}

Notice::Level severity_level(std::uint8_t severity) {
  if (severity <= 3) return Notice::Level::Error;  // emergency .. error
  if (severity == 4) return Notice::Level::Warning;
  return Notice::Level::Info;
}

}  // namespace

const char* to_string(OperatorCommand command) {
  switch (command) {
    case OperatorCommand::Arm:
      return "arm";
    case OperatorCommand::Disarm:
      return "disarm";
    case OperatorCommand::Offboard:
      return "offboard";
    case OperatorCommand::Land:
      return "land";
  }
  return "unknown";
}

Bridge::Bridge(const BridgeConfig& config)
    : config_(config),
      profile_(config.autopilot),
      session_(profile_, config.params.heartbeat_timeout_s),
      sender_(config.params.ack_timeout_s, config.params.command_retries),
      mapper_(config.params.gravity_m_s2),
      estimator_(estimator_params(config.params)),
      supervisor_(config.params.cmd_timeout_s, config.params.heartbeat_timeout_s,
                  2.0 * config.params.ack_timeout_s),
      sequencer_(config.params.offboard_stream_s, config.params.auto_arm, kSequencerRetry_s),
      streams_(stream_plan(config.autopilot, stream_rates(config.params)),
               config.params.stream_reask_s),
      parameters_(parameter_rules(config.autopilot),
                  config.autopilot == Autopilot::Px4 ? mavlink::ParamEncoding::Bytewise
                                                     : mavlink::ParamEncoding::CCast,
                  config.params.param_read_timeout_s, config.params.param_read_tries,
                  config.params.param_refresh_s),
      estimator_health_(config.autopilot),
      encoder_(config.params.system_id != 0 ? static_cast<std::uint8_t>(config.params.system_id)
                                            : kProvisionalSystemId,
               static_cast<std::uint8_t>(config.params.component_id), config.signing_key) {
  out_.reserve(8);
  resend_.reserve(8);
  in_flight_.reserve(8);
  recent_texts_.reserve(kRecentTexts);
  held_replies_.reserve(4);
  notices_.reserve(16);
  replies_.reserve(4);
  seen_.hover_logged = estimator_.estimate();
  if (config.params.auto_arm) {
    note(Notice::Level::Warning,
         "auto_arm is on: the bridge switches the autopilot to offboard and ARMS IT BY ITSELF "
         "(simulation only, never on a vehicle with people near)");
  }
}

double Bridge::advance(double now_s) {
  if (std::isfinite(now_s) && now_s > now_s_) now_s_ = now_s;
  return now_s_;
}

AutopilotView Bridge::view(double now_s) const {
  AutopilotView v;
  v.link_ok = session_.link_ok(now_s);
  v.armed = session_.armed();
  v.mode = session_.mode();
  return v;
}

void Bridge::note(Notice::Level level, std::string text) {
  notices_.push_back({level, std::move(text)});
}

// --- frames from the autopilot ---------------------------------------------------------

void Bridge::on_frame(const mavlink::Frame& frame, double now_s) {
  const double now = advance(now_s);
  if (!session_.accept(frame, now)) return;
  if (!seen_.known) learn_identity(now);
  streams_.on_frame(frame.message_id, now);
  switch (frame.message_id) {
    case mav::CommandAck::kId:
      sender_.on_ack(mav::CommandAck::unpack(frame.payload.data()), encoder_.system_id(),
                     encoder_.component_id(), now);
      take_results(now);
      break;
    case mav::HighresImu::kId:
    case mav::ScaledImu::kId:
      on_imu(frame, now);
      break;
    case mav::LocalPositionNed::kId:
      on_local_position(frame, now);
      break;
    case mav::AttitudeQuaternion::kId:
      on_attitude(frame);
      break;
    case mav::SysStatus::kId:
      estimator_health_.on_sys_status(mav::SysStatus::unpack(frame.payload.data()));
      break;
    case mav::EstimatorStatus::kId:
      estimator_health_.on_estimator_flags(
          mav::EstimatorStatus::unpack(frame.payload.data()).flags);
      break;
    case mav::EkfStatusReport::kId:
      estimator_health_.on_estimator_flags(
          mav::EkfStatusReport::unpack(frame.payload.data()).flags);
      break;
    case mav::Event::kId:
      on_event(frame);
      break;
    case mav::ParamValue::kId:
      on_parameter(frame, now);
      break;
    default:
      break;
  }
  note_session_changes(now);
}

void Bridge::learn_identity(double now_s) {
  seen_.known = true;
  streams_.restart(now_s);
  parameters_.restart(now_s);
  const std::uint8_t system_id = config_.params.system_id != 0
                                     ? static_cast<std::uint8_t>(config_.params.system_id)
                                     : session_.system_id();
  encoder_.set_sender(system_id, static_cast<std::uint8_t>(config_.params.component_id));
  parameters_.set_context(ParameterContext{system_id});
  note(Notice::Level::Info, "autopilot found: system " + std::to_string(session_.system_id()) +
                                " component " + std::to_string(session_.component_id()) + ", " +
                                autopilot_name(session_.reported_autopilot()) +
                                "; the bridge speaks as system " + std::to_string(system_id) +
                                " component " + std::to_string(config_.params.component_id));
  if (session_.reported_autopilot() != profile_.mav_autopilot()) {
    note(Notice::Level::Error,
         std::string("--autopilot ") + to_string(profile_.kind()) + ", but the autopilot says " +
             autopilot_name(session_.reported_autopilot()) + " (MAV_AUTOPILOT " +
             std::to_string(session_.reported_autopilot()) +
             "): its modes will be misread and the mode commands will be wrong");
  }
}

void Bridge::note_session_changes(double now_s) {
  const bool link_ok = session_.link_ok(now_s);
  if (link_ok != seen_.link_ok) {
    seen_.link_ok = link_ok;
    if (link_ok) {
      note(Notice::Level::Info, "autopilot link up (HEARTBEAT from system " +
                                    std::to_string(session_.system_id()) + ")");
      // It may have rebooted: its streams and parameters are asked for again.
      streams_.restart(now_s);
      parameters_.restart(now_s);
    } else {
      note(Notice::Level::Error,
           format("autopilot link LOST: no HEARTBEAT for %.2f s (limit %.2f s)",
                  now_s - session_.last_heartbeat_s(), config_.params.heartbeat_timeout_s));
    }
  }
  if (!link_ok) return;
  if (session_.armed() != seen_.armed) {
    seen_.armed = session_.armed();
    note(Notice::Level::Info, seen_.armed ? "autopilot ARMED" : "autopilot disarmed");
  }
  if (session_.mode_name() != seen_.mode_name) {
    note(Notice::Level::Info, "autopilot mode " + session_.mode_name() + " (" +
                                  to_string(session_.mode()) + ")" +
                                  (seen_.mode_name.empty() ? "" : ", was " + seen_.mode_name));
    seen_.mode_name = session_.mode_name();
  }
  if (session_.landed_state() != seen_.landed) {
    seen_.landed = session_.landed_state();
    note(Notice::Level::Info, std::string("autopilot landed state: ") + to_string(seen_.landed));
  }
  if (session_.status_text_count() != seen_.status_texts) {
    seen_.status_texts = session_.status_text_count();
    note(severity_level(session_.status_severity()), "autopilot says: " + session_.status_text());
    if (recent_texts_.size() == kRecentTexts) recent_texts_.erase(recent_texts_.begin());
    recent_texts_.push_back({now_s, session_.status_text()});
  }
}

void Bridge::on_event(const mavlink::Frame& frame) {
  const auto event = mav::Event::unpack(frame.payload.data());
  // An event sent again (a ground station asked for it) is not news.
  if (event_seen_ && event.sequence == last_event_sequence_) return;
  event_seen_ = true;
  last_event_sequence_ = event.sequence;
  const EventText text = describe_px4_event(event);
  if (!text.for_operator) return;
  session_.report_text(text.text, text.level);
}

void Bridge::on_parameter(const mavlink::Frame& frame, double now_s) {
  const auto value = mav::ParamValue::unpack(frame.payload.data());
  if (!parameters_.on_value(value, now_s)) return;
  const std::string name = mav::param_id_string(value.param_id);
  for (const ParameterFinding& f : parameters_.findings()) {
    if (f.name != name) continue;
    note(f.ok ? Notice::Level::Info
              : (f.weight == ParameterWeight::Blocking ? Notice::Level::Error
                                                       : Notice::Level::Warning),
         "autopilot parameter " + name + " = " + format("%g", f.value) +
             (f.ok ? std::string(" (ok)")
                   : std::string(" (COVER needs ") + f.needed + ": " + f.why + ")"));
  }
  seed_hover_thrust();
}

// The autopilot's own hover thrust, before the estimator has learned anything: a better
// start than the configured one on a vehicle that learned it (ArduPilot's MOT_HOVER_LEARN).
void Bridge::seed_hover_thrust() {
  if (!config_.params.hover_thrust_from_autopilot || hover_seeded_ || estimator_.learning()) {
    return;
  }
  const char* name = profile_.kind() == Autopilot::Px4 ? "MPC_THR_HOVER" : "MOT_THST_HOVER";
  const auto value = parameters_.value(name);
  if (!value) return;
  const double before = estimator_.estimate();
  if (!estimator_.restart_from(*value)) return;
  hover_seeded_ = true;
  seen_.hover_logged = estimator_.estimate();
  note(Notice::Level::Info, std::string("hover thrust estimate starts at the autopilot's ") + name +
                                format(" %.3f (was %.3f)", estimator_.estimate(), before));
}

void Bridge::on_imu(const mavlink::Frame& frame, double now_s) {
  double specific_force_up = 0.0;
  if (frame.message_id == mav::HighresImu::kId) {
    highres_imu_seen_ = true;
    specific_force_up = -mav::HighresImu::unpack(frame.payload.data()).zacc;  // FRD z is down
  } else if (!highres_imu_seen_) {
    specific_force_up = -mav::ScaledImu::unpack(frame.payload.data()).zacc * kMilliGToMS2;
  } else {
    return;
  }
  if (!flying_our_thrust(now_s) || !estimator_.update(last_thrust_, specific_force_up, now_s)) {
    return;
  }
  note_estimate();
}

// Our thrust flies the UAV only in offboard, with our stream flowing, in the air.
bool Bridge::flying_our_thrust(double now_s) const {
  return view(now_s).cover_flying() && stream_.streaming_for_s(now_s) > 0.0 &&
         session_.landed_state() == LandedState::InAir &&
         last_thrust_ >= config_.params.estimator_min_thrust;
}

// The autopilot's own vertical velocity, while its estimator says it is valid.
void Bridge::on_local_position(const mavlink::Frame& frame, double now_s) {
  if (!estimator_health_.vertical_velocity_ok() || !flying_our_thrust(now_s)) return;
  const double velocity_up = -mav::LocalPositionNed::unpack(frame.payload.data()).vz;  // NED
  const bool was_aided = estimator_.velocity_aided();
  if (!estimator_.update_velocity(last_thrust_, velocity_up, now_s)) return;
  if (!was_aided) {
    note(Notice::Level::Info,
         "the autopilot's vertical velocity (LOCAL_POSITION_NED) aids the hover-thrust estimate");
  }
  note_estimate();
}

// cos(tilt) of the body's up axis: the (3,3) element of the body-to-NED rotation.
void Bridge::on_attitude(const mavlink::Frame& frame) {
  const auto a = mav::AttitudeQuaternion::unpack(frame.payload.data());
  const double x = a.q2, y = a.q3;
  estimator_.set_tilt_cos(1.0 - 2.0 * (x * x + y * y));
}

void Bridge::note_estimate() {
  const double estimate = estimator_.estimate();
  if (std::abs(estimate - seen_.hover_logged) > 0.01) {
    note(Notice::Level::Info, format("hover thrust estimate %.3f (was %.3f, +-%.3f)", estimate,
                                     seen_.hover_logged, estimator_.standard_deviation()));
    seen_.hover_logged = estimate;
  }
}

// --- the agent's commands --------------------------------------------------------------

const std::vector<mavlink::EncodedFrame>& Bridge::on_agent_command(const AgentCommand& command,
                                                                   double now_s) {
  out_.clear();
  setpoint_sent_ = false;
  const double now = advance(now_s);
  if (!fresh(command)) return out_;
  if (last_fresh_s_ >= 0.0) gaps_.add(now - last_fresh_s_);
  last_fresh_s_ = now;
  supervisor_.on_command(command.handover, now);
  if (command.release_payload && !last_release_) {
    CommandSpec gripper;
    gripper.command = mav::mav_cmd::kDoGripper;
    gripper.param[0] = 1.0F;  // gripper instance 1
    gripper.param[1] = 0.0F;  // GRIPPER_ACTION_RELEASE
    send_command(gripper, Origin::Gripper, "payload release", "", now, true);
  }
  last_release_ = command.release_payload;
  send_setpoint(command, now);
  if (command.handover) supervise(now, true);  // at once, not at the next tick
  return out_;
}

bool Bridge::fresh(const AgentCommand& command) {
  // Only a verbatim repeat is stale (a tool republishing one sample). An older stamp is
  // not: in realtime the agent's clock is the simulator's extrapolated, which steps back a
  // little when a late tick arrives, and a restarted agent counts its seq from 1 again.
  const char* why = nullptr;
  if (!is_flyable(command)) {
    why = "not flyable (NaN or out of range)";
  } else if (has_last_ && command.stamp_ns == last_stamp_ns_ && command.seq == last_seq_ &&
             last_sent_) {
    // A repeat of a command not sent yet (no autopilot heard then) goes: a lockstep agent
    // answers a tick published again with the same command, and the simulator waits for it.
    why = "a repeat of the previous one (same stamp and seq)";
  }
  if (why != nullptr) {
    if (!rejecting_) {
      note(Notice::Level::Warning, "UAV agent command seq " + std::to_string(command.seq) +
                                       " ignored: " + why + "; such commands count as missing");
      rejecting_ = true;
    }
    return false;
  }
  if (rejecting_) {
    note(Notice::Level::Info, "UAV agent commands usable again");
    rejecting_ = false;
  }
  has_last_ = true;
  last_stamp_ns_ = command.stamp_ns;
  last_seq_ = command.seq;
  return true;
}

void Bridge::send_setpoint(const AgentCommand& command, double now_s) {
  last_sent_ = session_.known();
  if (!last_sent_) return;  // no autopilot to target yet
  const mav::SetAttitudeTarget target =
      mapper_.map(command, estimator_.estimate(), session_.system_id(), session_.component_id());
  last_thrust_ = target.thrust;
  out_.push_back(encoder_.encode(target));
  setpoint_sent_ = true;
  stream_.on_sent(now_s);
}

// --- commands to the autopilot ---------------------------------------------------------

bool Bridge::send_command(const CommandSpec& spec, Origin origin, std::string what,
                          const std::string& request_id, double now_s, bool preempt) {
  if (!session_.known()) return false;
  const std::uint64_t token = next_token_++;
  const auto message =
      sender_.start(spec, session_.system_id(), session_.component_id(), token, now_s, preempt);
  take_results(now_s);  // a command it superseded
  if (!message) return false;
  note(origin == Origin::Failsafe ? Notice::Level::Error : Notice::Level::Info,
       what + " requested (" + command_name(spec.command) + ")" +
           (request_id.empty() ? "" : " for request '" + request_id + "'"));
  in_flight_.push_back({token, origin, request_id, std::move(what), spec});
  out_.push_back(encoder_.encode(*message));
  return true;
}

void Bridge::take_results(double now_s) {
  auto& results = sender_.results();
  for (const CommandResult& result : results) {
    for (std::size_t i = 0; i < in_flight_.size(); ++i) {
      if (in_flight_[i].token != result.token) continue;
      const InFlight flight = std::move(in_flight_[i]);
      in_flight_.erase(in_flight_.begin() + static_cast<std::ptrdiff_t>(i));
      finish(flight, result, now_s);
      break;
    }
  }
  results.clear();
}

void Bridge::finish(const InFlight& flight, const CommandResult& result, double now_s) {
  const std::string text =
      flight.what + ": " + to_string(result.outcome) + " (" + result.message + ")";
  note(result.outcome == CommandOutcome::Accepted ? Notice::Level::Info : Notice::Level::Warning,
       text);
  // Armed (or disarmed) from the answer, not a HEARTBEAT up to a second later: a task waiting
  // for the arming starts up to a second sooner.
  if (result.outcome == CommandOutcome::Accepted &&
      flight.spec.command == mav::mav_cmd::kComponentArmDisarm) {
    session_.on_arming_accepted(flight.spec.param[0] > 0.5F, now_s);
  }
  if (result.outcome == CommandOutcome::Accepted &&
      flight.spec.command == mav::mav_cmd::kDoSetMode) {
    const auto main = static_cast<std::uint8_t>(flight.spec.param[1]);
    const auto sub = static_cast<std::uint8_t>(flight.spec.param[2]);
    session_.on_mode_accepted(static_cast<std::uint8_t>(flight.spec.param[0]),
                              profile_.kind() == Autopilot::Px4
                                  ? mav::px4_mode::custom_mode(main, sub)
                                  : std::uint32_t{main},
                              now_s);
  }
  switch (flight.origin) {
    case Origin::Operator:
      if (result.outcome == CommandOutcome::Refused) {
        hold_refusal({flight.request_id, result.outcome, text}, now_s);
      } else {
        replies_.push_back({flight.request_id, result.outcome, text});
      }
      break;
    case Origin::Failsafe:
      supervisor_.on_land_result(result.outcome, now_s);
      break;
    case Origin::AutoOffboard:
      sequencer_.on_result(OffboardSequencer::Step::RequestOffboard, result.outcome, now_s);
      break;
    case Origin::AutoArm:
      sequencer_.on_result(OffboardSequencer::Step::RequestArm, result.outcome, now_s);
      break;
    case Origin::Gripper:
      break;
    case Origin::StreamRequest:
      streams_.on_result(result.outcome, result.message, now_s);
      break;
  }
}

const std::vector<mavlink::EncodedFrame>& Bridge::on_operator_request(OperatorCommand command,
                                                                      const std::string& request_id,
                                                                      double now_s) {
  out_.clear();
  const double now = advance(now_s);
  if (!session_.known() || !session_.link_ok(now)) {
    refuse(request_id, "no HEARTBEAT from the autopilot: the link is down");
    return out_;
  }
  CommandSpec spec;
  bool preempt = false;
  switch (command) {
    case OperatorCommand::Arm:
      spec = profile_.arm_command(true);
      break;
    case OperatorCommand::Disarm:
      spec = profile_.arm_command(false);
      preempt = true;
      break;
    case OperatorCommand::Offboard:
      if (const auto why = sequencer_.offboard_refusal(stream_.streaming_for_s(now))) {
        refuse(request_id, *why);
        return out_;
      }
      spec = profile_.offboard_command();
      break;
    case OperatorCommand::Land:
      spec = profile_.land_command();
      preempt = true;
      break;
  }
  const std::string what = std::string(to_string(command)) +
                           (command == OperatorCommand::Offboard
                                ? std::string(" (") + profile_.offboard_mode_name() + ")"
                                : std::string());
  if (!send_command(spec, Origin::Operator, what, request_id, now, preempt)) {
    refuse(request_id, std::string("a ") + command_name(spec.command) +
                           " is still waiting for the autopilot's answer; try again");
  }
  return out_;
}

void Bridge::hold_refusal(OperatorReply reply, double now_s) {
  held_replies_.push_back({std::move(reply), now_s - kReasonLookback_s, now_s + kReasonWait_s});
}

void Bridge::release_refusals(double now_s) {
  for (std::size_t i = 0; i < held_replies_.size();) {
    HeldReply& held = held_replies_[i];
    if (now_s < held.release_s) {
      ++i;
      continue;
    }
    std::string reasons;
    for (const RecentText& text : recent_texts_) {
      if (text.at_s < held.since_s) continue;
      reasons += (reasons.empty() ? "" : "; ") + text.text;
    }
    if (!reasons.empty()) held.reply.message += "; the autopilot says: " + reasons;
    replies_.push_back(std::move(held.reply));
    held_replies_.erase(held_replies_.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

void Bridge::refuse(const std::string& request_id, std::string why) {
  note(Notice::Level::Warning, "request '" + request_id + "' refused: " + why);
  replies_.push_back({request_id, CommandOutcome::Refused, std::move(why)});
}

// --- housekeeping ----------------------------------------------------------------------

const std::vector<mavlink::EncodedFrame>& Bridge::tick(double now_s) {
  out_.clear();
  const double now = advance(now_s);
  const bool ran = last_tick_s_ < 0.0 || now - last_tick_s_ <= kStalledTick_s;
  if (!ran && supervisor_.landing() == false && view(now).cover_flying()) {
    note(Notice::Level::Warning,
         format("housekeeping %.0f ms late (the bridge was descheduled): the command timeout "
                "is judged on the next pass",
                (now - last_tick_s_) * 1e3));
  }
  last_tick_s_ = now;
  note_session_changes(now);
  resend_.clear();
  sender_.poll(now, resend_);
  for (const mav::CommandLong& message : resend_) out_.push_back(encoder_.encode(message));
  take_results(now);
  supervise(now, ran);
  sequence(now);
  request_streams(now);
  read_parameters(now);
  note_health_changes(now);
  release_refusals(now);
  if (now >= next_heartbeat_s_) send_heartbeat(now);
  return out_;
}

void Bridge::request_streams(double now_s) {
  if (!session_.known() || !session_.link_ok(now_s) ||
      sender_.busy(mav::mav_cmd::kSetMessageInterval)) {
    return;
  }
  const auto spec = streams_.next_request(now_s);
  if (!spec) return;
  const char* name = "a stream";
  for (const StreamState& s : streams_.states(now_s)) {
    if (s.request.message_id == static_cast<std::uint32_t>(spec->param[0])) name = s.request.name;
  }
  const std::string what = std::string("stream ") + name +
                           format(" at %.0f Hz", 1e6 / static_cast<double>(spec->param[1]));
  if (!send_command(*spec, Origin::StreamRequest, what, "", now_s, false)) {
    streams_.on_result(CommandOutcome::NoAnswer, "not sent", now_s);
  }
}

void Bridge::read_parameters(double now_s) {
  if (!session_.known() || !session_.link_ok(now_s)) return;
  auto request = parameters_.next_request(now_s);
  if (!request) return;
  request->target_system = session_.system_id();
  request->target_component = session_.component_id();
  out_.push_back(encoder_.encode(*request));
}

void Bridge::note_health_changes(double now_s) {
  const std::string missing = streams_.missing_summary(now_s);
  if (missing != seen_.streams_missing) {
    note(missing.empty() ? Notice::Level::Info : Notice::Level::Warning,
         missing.empty() ? std::string("every stream asked of the autopilot arrives")
                         : "streams asked of the autopilot not arriving: " + missing);
    seen_.streams_missing = missing;
  }
  const std::string blocker = parameters_.flight_blocker();
  if (blocker != seen_.flight_blocker) {
    note(blocker.empty() ? Notice::Level::Info : Notice::Level::Error,
         blocker.empty() ? std::string("no autopilot parameter holds COVER's flights any more")
                         : "COVER's tasks are held: " + blocker);
    seen_.flight_blocker = blocker;
  }
  const EstimatorHealth health = estimator_health_.health();
  if (health.reported && health.text != seen_.estimator) {
    note(health.attitude_ok ? Notice::Level::Info : Notice::Level::Warning,
         "autopilot estimator: " + health.text);
    seen_.estimator = health.text;
  }
}

double Bridge::auto_disarm_s() const {
  if (profile_.kind() == Autopilot::Px4) {
    const auto delay = parameters_.value("COM_DISARM_PRFLT");
    return delay && *delay > 0.0 ? *delay + kPx4SpoolUp_s : -1.0;
  }
  const auto delay = parameters_.value("DISARM_DELAY");
  return delay && *delay > 0.0 ? *delay : -1.0;
}

void Bridge::supervise(double now_s, bool bridge_ran) {
  const SafetySupervisor::Decision decision = supervisor_.check(view(now_s), now_s, bridge_ran);
  if (decision.triggered) {
    note(Notice::Level::Error, "LAND commanded: " + supervisor_.reason());
    if (sequencer_.automatic()) {
      sequencer_.stop();
      note(Notice::Level::Warning, "automatic offboard/arm procedure ended by the failsafe");
    }
  }
  if (decision.reached) {
    note(Notice::Level::Info, "the autopilot is in its land mode (or disarmed): failsafe done");
  }
  if (decision.request_land && !send_command(profile_.land_command(), Origin::Failsafe,
                                             "land (failsafe)", "", now_s, true)) {
    supervisor_.on_land_result(CommandOutcome::NoAnswer, now_s);
  }
}

void Bridge::sequence(double now_s) {
  const bool was_automatic = sequencer_.automatic();
  const double streamed_s = stream_.streaming_for_s(now_s);
  const OffboardSequencer::Step step = sequencer_.next(view(now_s), streamed_s, now_s);
  if (was_automatic && !sequencer_.automatic()) {
    note(Notice::Level::Warning,
         "automatic offboard/arm procedure ended: the autopilot left offboard or disarmed (" +
             session_.mode_name() + "); the bridge will not take it back");
  }
  bool sent = true;
  if (step == OffboardSequencer::Step::RequestOffboard) {
    sent = send_command(profile_.offboard_command(), Origin::AutoOffboard,
                        std::string(profile_.offboard_mode_name()) +
                            format(" (auto_arm; setpoints streamed %.2f s at %.0f Hz)", streamed_s,
                                   stream_.rate_hz(now_s)),
                        "", now_s, false);
  } else if (step == OffboardSequencer::Step::RequestArm) {
    sent = send_command(profile_.arm_command(true), Origin::AutoArm, "arm (auto_arm)", "", now_s,
                        false);
  }
  if (!sent) sequencer_.on_result(step, CommandOutcome::Refused, now_s);
}

void Bridge::send_heartbeat(double now_s) {
  mav::Heartbeat heartbeat;
  heartbeat.type = mav::mav_type::kOnboardController;
  heartbeat.autopilot = mav::mav_autopilot::kInvalid;
  heartbeat.base_mode = 0;
  heartbeat.custom_mode = 0;
  heartbeat.system_status = mav::mav_state::kActive;
  out_.push_back(encoder_.encode(heartbeat));
  next_heartbeat_s_ = now_s + kCompanionHeartbeatPeriod_s;
}

FcStatus Bridge::state(double now_s) const {
  const double now = std::isfinite(now_s) && now_s > now_s_ ? now_s : now_s_;
  FcStatus s;
  s.link_ok = session_.link_ok(now);
  s.reported_autopilot = session_.reported_autopilot();
  s.system_id = session_.system_id();
  s.armed = session_.armed();
  s.mode = session_.mode();
  s.mode_name = session_.mode_name();
  s.custom_mode = session_.custom_mode();
  s.landed_state = session_.landed_state();
  s.battery_voltage_v = session_.battery_voltage_v();
  s.battery_remaining = session_.battery_remaining();
  s.hover_thrust = estimator_.estimate();
  s.setpoint_rate_hz = stream_.rate_hz(now);
  s.rx_errors = parser_stats_.errors();
  s.rx_dropped = parser_stats_.sequence_gaps;
  s.rx_unknown = parser_stats_.unknown_frames;
  s.status_text = session_.status_text();
  s.offboard_ready = view(now).cover_flying();
  s.failsafe = supervisor_.reason();
  s.streams = streams_.states(now);
  s.streams_missing = streams_.missing_summary(now);
  s.estimator = estimator_health_.health();
  s.parameters = parameters_.findings();
  s.flight_blocker = parameters_.flight_blocker();
  s.auto_disarm_s = auto_disarm_s();
  return s;
}

}  // namespace cover::fc_bridge
