#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cover/task_manager/live_view.hpp"
#include "cover/task_manager/task_limits.hpp"
#include "cover/task_manager/task_store.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::task_manager {

struct Dispatch {  // send this task to that UAV (cover/task/request)
  int uav_id = 0;
  TaskRecord record;
};
struct AbortOnUav {  // send this abort (cover/task/abort)
  int uav_id = 0;
  std::string task_id;
  std::string reason;
};
struct Waiting {  // a queued task whose reason for waiting changed (recorded; log it)
  std::string task_id;
  std::string reason;
};
struct Actions {
  std::vector<Dispatch> dispatch;
  std::vector<AbortOnUav> abort;
  std::vector<Waiting> waiting;
};

// The manager's logic over the store: one queue per UAV, served in submission order, each
// task advanced from what its agent reports. Pure: no threads, no DDS, no clock (times are
// passed in). Everything that must survive a restart is in the store; a new Dispatcher on
// the same store re-learns Dispatched/Running tasks from the reports.
class Dispatcher {
 public:
  Dispatcher(TaskStore& store, TaskLimits limits);

  const TaskLimits& limits() const { return limits_; }

  // Validates (why_not_flyable) and stores: Queued, or Rejected with the reason. Idempotent
  // by the id of a task accepted: a repeat returns the stored record, created = false,
  // whatever the live view (answer_submission tells a repeat from other content under the
  // id). A submission rejected at once holds no id: the next one with it is judged anew
  // and replaces it.
  // A submission that cannot be recorded (why_not_recordable) throws std::invalid_argument
  // and stores nothing: check it first.
  TaskStore::SubmitResult submit(const mission::Task& task, const std::string& submitter,
                                 const std::string& request_id, const LiveView& live, double now_s);

  // Queued: becomes Aborted. Dispatched / Running: returns the AbortOnUav to send; the task
  // becomes Aborted when the agent reports it Cancelled, and step() re-sends the abort until
  // then. Final or unknown: ok = false with the reason.
  struct AbortResult {
    bool ok = false;
    std::string message;
    std::optional<AbortOnUav> send;
  };
  AbortResult abort(const std::string& task_id, const std::string& reason, double now_s);

  // Called periodically and on every new report: advances every Dispatched/Running task from
  // its agent's report, then dispatches the next Queued task to every UAV that has none in
  // flight and whose agent is up and idle. Where a flight-controller bridge runs for the UAV
  // (its autopilot is in the live view), only while the autopilot is ready (armed, in its
  // offboard mode, link up, the bridge heard within heartbeat_timeout_s); until then the
  // task stays queued and its reason says what it waits for ("waiting for UAV 0: autopilot
  // disarmed"). Returns what to send.
  Actions step(const LiveView& live, double now_s);

 private:
  void advance(const TaskRecord& record, const LiveView& live, double now_s);
  void advance_reported(const TaskRecord& record, const AgentReport& report, double now_s);
  void advance_unreported(const TaskRecord& record, const AgentReport& report, double now_s);
  void finish(const TaskRecord& record, TaskState to, const std::string& reason, double now_s);
  void note_failsafe(const TaskRecord& record, const AgentReport& report, double now_s);
  bool agent_up(const LiveView& live, int uav_id, double now_s) const;
  double silence_s(const LiveView& live, int uav_id, double now_s) const;
  void dispatch_idle_uavs(const LiveView& live, double now_s, Actions& actions);
  // Why the UAV's autopilot cannot fly a task now; nullopt when it can or has no bridge.
  std::optional<std::string> autopilot_not_ready(const LiveView& live, int uav_id,
                                                 double now_s) const;
  void note_waiting(const TaskRecord& next, const std::string& reason, double now_s,
                    Actions& actions);
  void resend_untaken_dispatches(const LiveView& live, double now_s, Actions& actions);

  static constexpr double kResendPeriod_s = 1.0;

  TaskStore& store_;
  TaskLimits limits_;
  // Aborts sent for tasks in flight, by task id, re-sent until the agent confirms. Held in
  // memory only: after a restart the operator's abort must be repeated.
  std::map<std::string, AbortOnUav> pending_aborts_;
  // The first step's time: an agent this Dispatcher has never heard counts as silent from
  // then, not from the epoch (a restarted manager waits for the heartbeats).
  std::optional<double> started_s_;
  // When each Dispatched task was last sent (memory only: a restart re-sends at once).
  std::map<std::string, double> last_sent_s_;
  // The failsafe each task in flight was last seen in (memory only): every change after
  // the first report is a history row.
  std::map<std::string, std::string> failsafe_seen_;
  // The reason each waiting queued task was last given (memory only): the store is written
  // when it changes, not on every step.
  std::map<std::string, std::string> waiting_noted_;
};

}  // namespace cover::task_manager
