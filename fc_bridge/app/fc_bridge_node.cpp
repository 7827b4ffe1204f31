#include "fc_bridge_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "cover/clock/clock.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "fc_messages.hpp"

namespace cover::fc_bridge {
namespace {
constexpr std::chrono::milliseconds kHousekeepingPeriod{20};  // 50 Hz
constexpr std::size_t kRecentRequests = 64;
// Lockstep: the agent's commands drive the bridge's tick; after this much simulated time
// without one, the housekeeping thread ticks instead (the supervisor's cmd timeout).
constexpr double kLockstepSilentTicks_s = 0.02;
// Lockstep: how long a command waits for the autopilot's frames of the step before it
// (they come within a millisecond; this bounds the wait for an autopilot that stopped).
constexpr std::chrono::milliseconds kStepFramesWait{250};
double monotonic_s() {
  return clock::ns_to_s(clock::monotonic_ns());
}
}  // namespace

FcBridgeNode::FcBridgeNode(dds::Participant& participant, NodeOptions options,
                           std::unique_ptr<mavlink::Link> link)
    : options_(std::move(options)),
      clock_(participant, options_.clock, !options_.step_frames),
      bridge_(options_.bridge),
      state_writer_(participant.make_writer(dds::topics::fc_state(options_.uav_id))),
      reply_writer_(participant.make_writer(dds::topics::fc_reply())),
      link_(std::move(link), options_.parser),
      command_reader_(
          participant.make_reader(dds::topics::uav_command(options_.uav_id),
                                  [this](const msg::UavCommand& command) { on_command(command); })),
      request_reader_(participant.make_reader(
          dds::topics::fc_request(),
          [this](const msg::FcRequest& request) { on_request(request); })) {}

FcBridgeNode::~FcBridgeNode() {
  // The readers' callbacks and the link's thread go before the members they use.
  command_reader_ = {};
  request_reader_ = {};
  link_.stop();
}

bool FcBridgeNode::start() {
  return link_.start([this](const mavlink::Frame& frame, const mavlink::ParserStats& stats) {
    on_frame(frame, stats);
  });
}

void FcBridgeNode::run() {
  while (!process::ShutdownSignal::requested()) {
    clock_.wait(next_wait());
    if (const auto now = clock_.now_s()) housekeeping(*now);
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    spdlog::info("{}", bridge_.command_gaps().summary(options_.bridge.params.cmd_timeout_s));
  }
  spdlog::info("stopping: {} frame(s) could not be written to the link", write_failures_);
}

// The housekeeping period, cut short so that a pass runs just after the command timeout
// would expire: the agent's silence is then judged at the timeout, not up to a period later.
// Lockstep keeps the period: its time comes in ticks.
std::chrono::milliseconds FcBridgeNode::next_wait() const {
  const double last = last_command_tick_s_.load();
  const auto now = clock_.now_s();
  if (lockstep() || !now || last < 0.0) return kHousekeepingPeriod;
  const double until_s = last + options_.bridge.params.cmd_timeout_s - *now + 1e-3;
  const auto until = std::chrono::milliseconds(static_cast<long>(std::ceil(until_s * 1e3)));
  if (until_s <= 0.0 || until >= kHousekeepingPeriod) return kHousekeepingPeriod;
  return std::max(until, std::chrono::milliseconds(1));
}

// --- the three inputs ------------------------------------------------------------------

void FcBridgeNode::on_command(const msg::UavCommand& command) {
  clock_.observe_command_stamp(command.stamp_ns);
  const auto now = clock_.now_s();
  if (!now) return;  // no simulator time yet
  last_command_tick_s_ = *now;
  const AgentCommand c = from_msg(command);
  Events events;
  std::optional<FcStatus> status;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    // Lockstep: the frames of the step before are taken first; the tick's own decisions
    // (mode and arm requests, retries, the land supervisor) go out just before its
    // setpoint, from this thread, so the simulated autopilot meets them at the same tick in
    // every run.
    if (step_frames()) await_step_frames_locked(lock, *now);
    if (lockstep()) write_locked(bridge_.tick(*now));
    write_locked(bridge_.on_agent_command(c, *now));
    if (step_frames() && bridge_.setpoint_sent()) steps_.flown(*now);
    // A real firmware in lockstep: the agent's next tick waits for a state of this one.
    if (lockstep() && !step_frames()) status = bridge_.state(*now);
    take_events_locked(events);
  }
  if (!events.empty()) report(events);
  if (status) write_state(*status, *now, true);
}

void FcBridgeNode::await_step_frames_locked(std::unique_lock<std::mutex>& lock, double tick_s) {
  if (steps_.wait(lock, tick_s, std::chrono::steady_clock::now() + kStepFramesWait)) return;
  if (step_frames_late_logged_) return;
  step_frames_late_logged_ = true;
  spdlog::warn(
      "tick {:.2f} s: the autopilot's frames of step {:.2f} s (closed by its HIGHRES_IMU) not in "
      "after {} ms; the command goes on without them, and this lockstep run will not repeat "
      "bit for bit (logged once)",
      tick_s, steps_.flown_s(), kStepFramesWait.count());
}

void FcBridgeNode::on_request(const msg::FcRequest& request) {
  if (request.uav_id != options_.uav_id || seen_before(request.request_id)) return;
  const auto kind = from_msg(request.kind);
  spdlog::info("operator request '{}' from {}: {}", request.request_id, request.submitter,
               kind ? to_string(*kind) : "unknown");
  const auto now = clock_.now_s();
  if (!kind || !now) {
    reply(request.request_id, msg::FcCommandResult::FC_RESULT_REFUSED,
          !kind ? "unknown command kind" : "the bridge has no time yet (no simulator clock)");
    return;
  }
  Events events;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    write_locked(bridge_.on_operator_request(*kind, request.request_id, *now));
    take_events_locked(events);
  }
  report(events);
}

void FcBridgeNode::on_frame(const mavlink::Frame& frame, const mavlink::ParserStats& stats) {
  Events events;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // Lockstep: a frame belongs to the step the last setpoint flew (it came after that
    // setpoint, and the next command waits for it), whatever the simulator's clock says by
    // the time this thread runs.
    const auto now = step_frames() && steps_.flown_s() >= 0.0
                         ? std::optional<double>(steps_.flown_s())
                         : clock_.now_s();
    if (!now) return;
    bridge_.set_parser_stats(stats);
    bridge_.on_frame(frame, *now);
    if (step_frames() && frame.message_id == mavlink::HighresImu::kId) close_step_locked(frame);
    take_events_locked(events);
  }
  if (!events.empty()) report(events);
}

void FcBridgeNode::close_step_locked(const mavlink::Frame& frame) {
  const double step_s =
      1e-6 * static_cast<double>(mavlink::HighresImu::unpack(frame.payload.data()).time_usec);
  steps_.frames_in(step_s);
  // The agent's next tick waits for the state after this step (its FcGate).
  write_state(bridge_.state(step_s), step_s, true);
}

void FcBridgeNode::housekeeping(double now_s) {
  Events events;
  std::optional<FcStatus> status;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // Lockstep: ticked on each command (on_command) while the agent answers; here only when
    // it has fallen silent (the supervisor must still see that), never racing a setpoint.
    const bool agent_silent = now_s - last_command_tick_s_ > kLockstepSilentTicks_s;
    if (!lockstep() || agent_silent) write_locked(bridge_.tick(now_s));
    if (!step_frames()) {
      status = bridge_.state(now_s);
    } else if (steps_.in_s() < 0.0 || agent_silent) {
      // Lockstep: the state goes out with each step's frames (close_step_locked); here only
      // while none come, stamped with the newest step it includes.
      write_state(bridge_.state(now_s), std::max(steps_.in_s(), 0.0), false);
    }
    take_events_locked(events);
  }
  if (!events.empty()) report(events);
  if (status) write_state(*status, now_s, false);
}

// --- outputs ---------------------------------------------------------------------------

void FcBridgeNode::write_locked(const std::vector<mavlink::EncodedFrame>& frames) {
  // A frame the link cannot take is counted, not logged: the link's loss and return are
  // logged by its keeper, and a udpin link without a peer yet is not news.
  for (const mavlink::EncodedFrame& frame : frames) {
    if (!link_.write(frame.bytes.data(), frame.size)) ++write_failures_;
  }
}

void FcBridgeNode::take_events_locked(Events& events) {
  if (!bridge_.notices().empty()) events.notices.swap(bridge_.notices());
  if (!bridge_.replies().empty()) events.replies.swap(bridge_.replies());
}

void FcBridgeNode::report(Events& events) {
  for (const Notice& notice : events.notices) {
    switch (notice.level) {
      case Notice::Level::Info:
        spdlog::info("{}", notice.text);
        break;
      case Notice::Level::Warning:
        spdlog::warn("{}", notice.text);
        break;
      case Notice::Level::Error:
        spdlog::error("{}", notice.text);
        break;
    }
  }
  for (const OperatorReply& r : events.replies) reply(r.request_id, to_msg(r.outcome), r.message);
}

void FcBridgeNode::reply(const std::string& request_id, msg::FcCommandResult result,
                         const std::string& message) {
  msg::FcReply r;
  r.request_id = request_id;
  r.uav_id = options_.uav_id;
  r.stamp_ns = clock::system_ns();
  r.result = result;
  r.message = message;
  reply_writer_.write(r);
  spdlog::info("reply to '{}': {}", request_id, message);
}

bool FcBridgeNode::seen_before(const std::string& request_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (std::find(recent_requests_.begin(), recent_requests_.end(), request_id) !=
      recent_requests_.end()) {
    return true;
  }
  recent_requests_.push_back(request_id);
  if (recent_requests_.size() > kRecentRequests) recent_requests_.pop_front();
  return false;
}

void FcBridgeNode::write_state(const FcStatus& status, double stamp_s, bool every_step) {
  msg::FcState state = to_msg(status, options_.uav_id, clock::s_to_ns(stamp_s));
  // Paced on the host's clock: readers judge a silent bridge by wall time.
  const double wall_s = monotonic_s();
  const bool due = every_step || wall_s >= next_state_monotonic_s_;
  if (!due && last_state_ && !differs(state, *last_state_)) return;
  state_writer_.write(state);
  last_state_ = std::move(state);
  next_state_monotonic_s_ = wall_s + 1.0 / options_.bridge.params.state_rate_hz;
}

}  // namespace cover::fc_bridge
