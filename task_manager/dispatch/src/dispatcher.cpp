#include "cover/task_manager/dispatcher.hpp"

#include <cstdio>
#include <set>
#include <stdexcept>

#include "cover/task_manager/flyability.hpp"
#include "cover/task_manager/submission_answer.hpp"

namespace cover::task_manager {
namespace {
using AgentTask = AgentReport::AgentTask;

std::string seconds(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", value);
  return text;
}

std::string uav_name(int uav_id) {
  return "UAV " + std::to_string(uav_id);
}

bool agent_idle(AgentTask state) {
  return state != AgentTask::Pending && state != AgentTask::Running;
}

// The agent's own words when it gave any, else a fallback that names who said it.
std::string reason_or(const std::string& message, const std::string& fallback) {
  return message.empty() ? fallback : message;
}
}  // namespace

Dispatcher::Dispatcher(TaskStore& store, TaskLimits limits)
    : store_(store), limits_(std::move(limits)) {
  limits_.validate();
}

TaskStore::SubmitResult Dispatcher::submit(const mission::Task& task, const std::string& submitter,
                                           const std::string& request_id, const LiveView& live,
                                           double now_s) {
  if (auto why = why_not_recordable(task, submitter, request_id)) throw std::invalid_argument(*why);
  // A task accepted holds its id; a submission rejected at once holds nothing: judged anew.
  if (auto existing = store_.find(task.task_id); existing && existing->accepted) {
    return {false, false, std::move(*existing)};
  }
  if (auto why = why_not_flyable(task, live, limits_, now_s)) {
    return store_.submit(task, submitter, request_id, TaskState::Rejected, *why, now_s);
  }
  return store_.submit(task, submitter, request_id, TaskState::Queued, queued_message(task.uav_id),
                       now_s);
}

Dispatcher::AbortResult Dispatcher::abort(const std::string& task_id, const std::string& reason,
                                          double now_s) {
  const auto record = store_.find(task_id);
  if (!record) return {false, "no task '" + task_id + "'", std::nullopt};
  if (is_final(record->state)) {
    return {false, "task '" + task_id + "' is already " + to_string(record->state), std::nullopt};
  }
  if (record->state == TaskState::Queued) {
    waiting_noted_.erase(task_id);
    store_.set_state(task_id, TaskState::Aborted, reason, now_s);
    return {true, "task '" + task_id + "' aborted before it was dispatched", std::nullopt};
  }
  // In flight: only the agent knows when it has stopped; the abort stands until it says so.
  const auto [entry, inserted] =
      pending_aborts_.emplace(task_id, AbortOnUav{record->uav_id, task_id, reason});
  return {true, "abort sent to " + uav_name(record->uav_id), entry->second};
}

Actions Dispatcher::step(const LiveView& live, double now_s) {
  if (!started_s_) started_s_ = now_s;
  for (const TaskRecord& record : store_.in_states({TaskState::Dispatched, TaskState::Running})) {
    advance(record, live, now_s);
  }
  Actions actions;
  for (auto it = pending_aborts_.begin(); it != pending_aborts_.end();) {
    const auto record = store_.find(it->first);
    if (!record || is_final(record->state)) {
      it = pending_aborts_.erase(it);
    } else {
      actions.abort.push_back(it->second);
      ++it;
    }
  }
  resend_untaken_dispatches(live, now_s, actions);
  dispatch_idle_uavs(live, now_s, actions);
  return actions;
}

// A dispatch can be lost (the manager killed between recording it and sending it, a reader
// not yet matched): while the agent is up, idle and reports another task, send it again.
// Never to an agent that reports this task in any state: it would fly it twice.
void Dispatcher::resend_untaken_dispatches(const LiveView& live, double now_s, Actions& actions) {
  for (const TaskRecord& record : store_.in_states({TaskState::Dispatched})) {
    const auto agent = live.agents.find(record.uav_id);
    if (agent == live.agents.end() || !agent_up(live, record.uav_id, now_s)) continue;
    const AgentReport& report = agent->second;
    if (report.task_id == record.task_id || !agent_idle(report.task_state)) continue;
    double& last = last_sent_s_[record.task_id];
    if (last > 0.0 && now_s - last < kResendPeriod_s) continue;
    last = now_s;
    actions.dispatch.push_back({record.uav_id, record});
  }
}

void Dispatcher::advance(const TaskRecord& record, const LiveView& live, double now_s) {
  const double silence = silence_s(live, record.uav_id, now_s);
  if (silence > limits_.heartbeat_timeout_s) {
    finish(record, TaskState::Failed,
           uav_name(record.uav_id) + " went silent (no heartbeat for " + seconds(silence) + ")",
           now_s);
    return;
  }
  const auto agent = live.agents.find(record.uav_id);
  if (agent == live.agents.end()) return;  // not heard yet since a restart: wait for it
  const AgentReport& report = agent->second;
  if (report.task_id == record.task_id && report.task_state != AgentTask::None) {
    advance_reported(record, report, now_s);
  } else {
    advance_unreported(record, report, now_s);
  }
}

void Dispatcher::advance_reported(const TaskRecord& record, const AgentReport& report,
                                  double now_s) {
  const std::string uav = uav_name(record.uav_id);
  switch (report.task_state) {
    case AgentTask::None:
      return;
    case AgentTask::Pending:
    case AgentTask::Running:
      if (record.state == TaskState::Dispatched) {
        store_.set_state(record.task_id, TaskState::Running,
                         reason_or(report.message, uav + " runs it"), now_s);
      }
      note_failsafe(record, report, now_s);
      return;
    case AgentTask::Succeeded:
      finish(record, TaskState::Succeeded, reason_or(report.message, uav + " succeeded"), now_s);
      return;
    case AgentTask::Failed:
      finish(record, TaskState::Failed, reason_or(report.message, uav + " failed"), now_s);
      return;
    case AgentTask::Cancelled: {
      const auto pending = pending_aborts_.find(record.task_id);
      const std::string asked =
          pending == pending_aborts_.end() ? uav + " cancelled it" : pending->second.reason;
      finish(record, TaskState::Aborted, reason_or(report.message, asked), now_s);
      return;
    }
    case AgentTask::Rejected:
      finish(record, TaskState::Rejected, reason_or(report.message, uav + " rejected it"), now_s);
      return;
  }
}

// The agent is heard but reports another task, or none.
void Dispatcher::advance_unreported(const TaskRecord& record, const AgentReport& report,
                                    double now_s) {
  const std::string uav = uav_name(record.uav_id);
  if (record.state == TaskState::Dispatched) {
    // From the dispatch, or from this manager's start: the time it was down is not the
    // agent's fault.
    const double since_s = std::max(record.updated_s, *started_s_);
    if (now_s - since_s <= limits_.dispatch_timeout_s) return;
    const auto pending = pending_aborts_.find(record.task_id);
    if (pending != pending_aborts_.end()) {
      finish(record, TaskState::Aborted, pending->second.reason + " (" + uav + " never took it)",
             now_s);
    } else {
      finish(record, TaskState::Failed,
             uav + " did not take the task within " + seconds(limits_.dispatch_timeout_s), now_s);
    }
    return;
  }
  // Running here, but the agent flies nothing or something else: our task is gone from it
  // (the agent restarted, or someone else gave it a task).
  if (agent_idle(report.task_state)) {
    finish(record, TaskState::Failed, uav + " came back idle", now_s);
  } else {
    finish(record, TaskState::Failed, uav + " flies another task '" + report.task_id + "'", now_s);
  }
}

void Dispatcher::finish(const TaskRecord& record, TaskState to, const std::string& reason,
                        double now_s) {
  store_.set_state(record.task_id, to, reason, now_s);
  pending_aborts_.erase(record.task_id);
  last_sent_s_.erase(record.task_id);
  failsafe_seen_.erase(record.task_id);
}

// A failsafe entry or exit during the flight: a history row with the agent's cause.
void Dispatcher::note_failsafe(const TaskRecord& record, const AgentReport& report, double now_s) {
  if (report.failsafe.empty()) return;
  const auto seen = failsafe_seen_.find(record.task_id);
  if (seen == failsafe_seen_.end()) {
    failsafe_seen_[record.task_id] = report.failsafe;
    return;
  }
  if (seen->second == report.failsafe) return;
  store_.note(record.task_id,
              uav_name(record.uav_id) + " failsafe " + seen->second + " -> " + report.failsafe +
                  (report.message.empty() ? "" : ": " + report.message),
              now_s);
  seen->second = report.failsafe;
}

std::optional<std::string> Dispatcher::autopilot_not_ready(const LiveView& live, int uav_id,
                                                           double now_s) const {
  const auto autopilot = live.autopilots.find(uav_id);
  if (autopilot == live.autopilots.end()) return std::nullopt;  // no bridge: direct path
  const double silence_s = now_s - autopilot->second.heard_s;
  if (silence_s > limits_.heartbeat_timeout_s) {
    // A bridge that stopped reporting is not taken for gone: its autopilot's state is unknown.
    return "its flight-controller bridge not heard for " + seconds(silence_s);
  }
  if (autopilot->second.not_ready.empty()) return std::nullopt;
  return autopilot->second.not_ready;
}

void Dispatcher::note_waiting(const TaskRecord& next, const std::string& reason, double now_s,
                              Actions& actions) {
  std::string& noted = waiting_noted_[next.task_id];
  if (noted == reason) return;
  noted = reason;
  store_.set_reason(next.task_id, reason, now_s);
  actions.waiting.push_back({next.task_id, reason});
}

bool Dispatcher::agent_up(const LiveView& live, int uav_id, double now_s) const {
  const auto agent = live.agents.find(uav_id);
  return agent != live.agents.end() && now_s - agent->second.heard_s <= limits_.heartbeat_timeout_s;
}

double Dispatcher::silence_s(const LiveView& live, int uav_id, double now_s) const {
  const auto agent = live.agents.find(uav_id);
  if (agent != live.agents.end()) return now_s - agent->second.heard_s;
  // Never heard since this start: silent only once the restart grace has passed.
  const double grace_left_s = limits_.restart_grace_s - limits_.heartbeat_timeout_s;
  return now_s - *started_s_ - grace_left_s;
}

void Dispatcher::dispatch_idle_uavs(const LiveView& live, double now_s, Actions& actions) {
  std::set<int> busy;
  for (const TaskRecord& record : store_.in_states({TaskState::Dispatched, TaskState::Running})) {
    busy.insert(record.uav_id);
  }
  for (const auto& [uav_id, report] : live.agents) {
    if (busy.count(uav_id) || !agent_up(live, uav_id, now_s)) continue;
    // An agent flying a task the store does not count as in flight (one that timed out here,
    // or one given on its command line) is left alone.
    if (!agent_idle(report.task_state)) continue;
    auto next = store_.next_queued(uav_id);
    if (!next) continue;
    if (const auto why = autopilot_not_ready(live, uav_id, now_s)) {
      note_waiting(*next, "waiting for " + uav_name(uav_id) + ": " + *why, now_s, actions);
      continue;
    }
    waiting_noted_.erase(next->task_id);
    const std::string reason = "sent to " + uav_name(uav_id);
    if (!store_.set_state(next->task_id, TaskState::Dispatched, reason, now_s)) continue;
    next->state = TaskState::Dispatched;
    next->updated_s = now_s;
    next->reason = reason;
    last_sent_s_[next->task_id] = now_s;
    actions.dispatch.push_back({uav_id, std::move(*next)});
  }
}

}  // namespace cover::task_manager
