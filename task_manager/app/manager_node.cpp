#include "manager_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/task_manager/flyability.hpp"
#include "cover/task_manager/submission_answer.hpp"
#include "cover/wire/task.hpp"
#include "managed_task_msg.hpp"

namespace cover::task_manager {
namespace {

// Far more than the requests in flight from every station within a resend period.
constexpr std::size_t kRememberedReplies = 1024;

// "1.0 s", "8.3 s".
std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", seconds);
  return text;
}

msg::ManagerReply reply_to(const msg::ManagerRequest& request, bool ok, std::string message) {
  msg::ManagerReply reply;
  reply.request_id = request.request_id;
  reply.stamp_ns = clock::system_ns();
  reply.ok = ok;
  reply.message = std::move(message);
  return reply;
}

}  // namespace

ManagerNode::ManagerNode(dds::Participant& participant, TaskStore& store, TaskLimits limits,
                         ManagerOptions options)
    : store_(store),
      dispatcher_(store, limits),
      options_(options),
      fleet_(participant, options.max_uavs, options.max_ugvs),
      reply_writer_(participant.make_writer(dds::topics::manager_reply())),
      dispatch_writer_(participant.make_writer(dds::topics::task_request())),
      abort_writer_(participant.make_writer(dds::topics::task_abort())),
      listening_since_s_(clock::system_s()),
      listen_first_s_(limits.heartbeat_timeout_s) {
  request_reader_ = participant.make_reader(
      dds::topics::manager_request(), [this](const msg::ManagerRequest& r) { on_request(r); });
}

void ManagerNode::on_request(const msg::ManagerRequest& request) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    requests_.push_back(request);
  }
  arrived_.notify_one();
}

int ManagerNode::run() {
  const auto period = std::chrono::milliseconds(static_cast<long>(options_.step_period_s * 1000));
  while (!process::ShutdownSignal::requested()) {
    std::deque<msg::ManagerRequest> batch;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      arrived_.wait_for(lock, period, [this] { return !requests_.empty(); });
      batch.swap(requests_);
    }
    const double now = clock::system_s();
    // In submission order: a submission waits while any before it does.
    while (!held_.empty() && !why_wait(held_.front().request, now)) {
      handle(held_.front().request, now);
      held_.pop_front();
    }
    for (const msg::ManagerRequest& request : batch) {
      if (request.kind == msg::ManagerRequestKind::MANAGER_SUBMIT) {
        take_submission(request, now);
      } else {
        handle(request, now);
      }
    }
    step(now);
  }
  spdlog::info("shutting down");
  return 0;
}

std::optional<ManagerNode::Wait> ManagerNode::why_wait(const msg::ManagerRequest& request,
                                                       double now_s) const {
  const double listened_s = now_s - listening_since_s_;
  if (listened_s < listen_first_s_) {
    return Wait{"the fleet",
                "waiting: the task manager has just started and listens to the fleet for " +
                    seconds_text(listen_first_s_) + " before it judges a task"};
  }
  const TaskLimits& limits = dispatcher_.limits();
  if (listened_s >= limits.restart_grace_s) return std::nullopt;
  try {
    const mission::Task task = wire::from_msg(request.task);
    // A submission refused or rejected for its own faults is answered at once.
    if (why_not_recordable(task, request.submitter, request.request_id)) return std::nullopt;
    if (why_not_sound(task, limits)) return std::nullopt;
    const auto unheard = first_unheard(task, fleet_.view(), options_.max_uavs, options_.max_ugvs);
    if (!unheard) return std::nullopt;
    return Wait{*unheard, "waiting for " + *unheard + " (not heard yet; decided within " +
                              seconds_text(limits.restart_grace_s - listened_s) + ")"};
  } catch (const std::exception&) {
    return std::nullopt;  // handle() reports it
  }
}

std::size_t ManagerNode::held_position(const std::string& request_id) const {
  const auto held = std::find_if(held_.begin(), held_.end(),
                                 [&](const Held& h) { return h.request.request_id == request_id; });
  return static_cast<std::size_t>(held - held_.begin());
}

void ManagerNode::take_submission(const msg::ManagerRequest& request, double now_s) {
  if (answered_.count(request.request_id) > 0) {
    handle(request, now_s);  // a repeat of a decided one: its first answer again
    return;
  }
  const std::size_t position = held_position(request.request_id);
  auto why = why_wait(request, now_s);
  if (!why && position > 0 && !held_.empty()) {
    // In submission order: behind the first held one, which says what it waits for.
    const std::size_t ahead = std::min(position, held_.size());
    why = Wait{"earlier submissions",
               "waiting behind " + std::to_string(ahead) + " earlier submission(s)"};
  }
  if (position < held_.size()) {
    // The station re-sends until decided: the same interim answer again, unless what the
    // submission waits for changed (the fleet heard, now UGV 7), so that it can tell news
    // from a repeat. First in line and no longer waiting: decided on the loop's next pass.
    Held& held = held_[position];
    if (why && why->what != held.why.what) {
      spdlog::info("submission {} from {} held: {}", request.request_id, request.submitter,
                   why->message);
      held.why = *why;
    }
    answer_interim(request, held.why.message);
    return;
  }
  if (!why) {
    handle(request, now_s);
    return;
  }
  spdlog::info("submission {} from {} held: {}", request.request_id, request.submitter,
               why->message);
  held_.push_back({request, *why});
  answer_interim(request, why->message);
}

void ManagerNode::answer_interim(const msg::ManagerRequest& request, const std::string& why) {
  msg::ManagerReply reply = reply_to(request, true, why);
  reply.interim = true;
  reply_writer_.write(reply);
}

void ManagerNode::handle(const msg::ManagerRequest& request, double now_s) {
  if (const auto seen = answered_.find(request.request_id); seen != answered_.end()) {
    reply_writer_.write(seen->second);
    return;
  }
  msg::ManagerReply reply;
  try {
    switch (request.kind) {
      case msg::ManagerRequestKind::MANAGER_SUBMIT:
        reply = submit(request, now_s);
        break;
      case msg::ManagerRequestKind::MANAGER_ABORT:
        reply = abort(request, now_s);
        break;
      case msg::ManagerRequestKind::MANAGER_QUERY:
        reply = query(request);
        break;
      default:
        reply = reply_to(request, false, "unknown request kind");
    }
  } catch (const std::exception& e) {
    // A store failure is reported, logged, and the manager keeps serving.
    spdlog::error("request {} from {}: {}", request.request_id, request.submitter, e.what());
    reply = reply_to(request, false, std::string("task manager error: ") + e.what());
  }
  reply_writer_.write(reply);
  answered_[request.request_id] = reply;
  answered_order_.push_back(request.request_id);
  if (answered_order_.size() > kRememberedReplies) {
    answered_.erase(answered_order_.front());
    answered_order_.pop_front();
  }
}

msg::ManagerReply ManagerNode::submit(const msg::ManagerRequest& request, double now_s) {
  const mission::Task task = wire::from_msg(request.task);
  if (auto why = why_not_recordable(task, request.submitter, request.request_id)) {
    spdlog::warn("a submission was refused unrecorded: {}", *why);
    return reply_to(request, false, "rejected: " + *why);
  }
  const TaskStore::SubmitResult result =
      dispatcher_.submit(task, request.submitter, request.request_id, fleet_.view(), now_s);
  const SubmissionAnswer answer = answer_submission(task, result);
  log_submission(request, result, answer);
  msg::ManagerReply reply = reply_to(request, answer.ok, answer.message);
  reply.tasks.push_back(to_msg(result.record));
  return reply;
}

void ManagerNode::log_submission(const msg::ManagerRequest& request,
                                 const TaskStore::SubmitResult& result,
                                 const SubmissionAnswer& answer) const {
  const TaskRecord& r = result.record;
  const char* replacing = result.replaced_rejected ? " (replacing a rejected submission)" : "";
  if (!result.created && answer.ok) {
    spdlog::info(
        "task '{}' from {}: the same as the task known under its id ({}), answered as "
        "the first time",
        r.task_id, request.submitter, to_string(r.state));
  } else if (!result.created) {
    spdlog::warn("task '{}' from {} refused: {}", r.task_id, request.submitter, answer.message);
  } else if (r.state == TaskState::Rejected) {
    spdlog::warn("task '{}' from {} rejected{}: {}", r.task_id, request.submitter, replacing,
                 r.reason);
  } else {
    spdlog::info("task '{}' from {} queued for UAV {} (position {}){}", r.task_id,
                 request.submitter, r.uav_id, r.queue_position, replacing);
  }
}

msg::ManagerReply ManagerNode::abort(const msg::ManagerRequest& request, double now_s) {
  const std::string reason =
      request.reason.empty() ? "aborted by " + request.submitter : request.reason;
  const Dispatcher::AbortResult result = dispatcher_.abort(request.task_id, reason, now_s);
  if (result.send) {
    msg::TaskAbort abort;
    abort.uav_id = static_cast<std::uint32_t>(result.send->uav_id);
    abort.stamp_ns = clock::system_ns();
    abort.task_id = result.send->task_id;
    abort.reason = result.send->reason;
    abort_writer_.write(abort);
  }
  spdlog::info("abort of '{}' from {}: {}", request.task_id, request.submitter, result.message);
  msg::ManagerReply reply = reply_to(request, result.ok, result.message);
  if (const auto record = store_.find(request.task_id)) reply.tasks.push_back(to_msg(*record));
  return reply;
}

msg::ManagerReply ManagerNode::query(const msg::ManagerRequest& request) const {
  if (request.task_id.empty()) {
    msg::ManagerReply reply = reply_to(request, true, "");
    for (const TaskRecord& r : store_.list(request.include_final)) reply.tasks.push_back(to_msg(r));
    return reply;
  }
  const auto record = store_.find(request.task_id);
  if (!record) return reply_to(request, false, "no task '" + request.task_id + "'");
  msg::ManagerReply reply = reply_to(request, true, "");
  reply.tasks.push_back(to_msg(*record));
  return reply;
}

void ManagerNode::step(double now_s) {
  const auto before = store_.in_states({TaskState::Dispatched, TaskState::Running});
  send(dispatcher_.step(fleet_.view(), now_s), now_s);
  for (const TaskRecord& r : before) {
    const auto after = store_.find(r.task_id);
    if (after && after->state != r.state) {
      spdlog::info("task '{}' on UAV {}: {} -> {} ({})", r.task_id, r.uav_id, to_string(r.state),
                   to_string(after->state), after->reason);
    }
  }
}

void ManagerNode::send(const Actions& actions, double now_s) {
  for (const Waiting& w : actions.waiting) {
    spdlog::info("task '{}' stays queued: {}", w.task_id, w.reason);
  }
  for (const Dispatch& d : actions.dispatch) {
    spdlog::info("task '{}' sent to UAV {}", d.record.task_id, d.uav_id);
    dispatch_writer_.write(wire::to_msg(d.record.task, now_s));
  }
  for (const AbortOnUav& a : actions.abort) {
    msg::TaskAbort abort;
    abort.uav_id = static_cast<std::uint32_t>(a.uav_id);
    abort.stamp_ns = clock::system_ns();
    abort.task_id = a.task_id;
    abort.reason = a.reason;
    abort_writer_.write(abort);
  }
}

}  // namespace cover::task_manager
