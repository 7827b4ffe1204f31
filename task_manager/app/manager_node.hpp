#pragma once

#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/task_manager/dispatcher.hpp"
#include "cover/task_manager/submission_answer.hpp"
#include "cover/task_manager/task_store.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "fleet_watch.hpp"

namespace cover::task_manager {

struct ManagerOptions {
  int max_uavs = fleet::kDefaultUavs;
  int max_ugvs = fleet::kDefaultUgvs;
  double step_period_s = 0.1;  // the dispatcher's pace when no request arrives
};

// cover-task-manager's DDS side: requests from ground stations in, replies out; tasks to
// the UAV agents (cover/task/request), aborts (cover/task/abort); the fleet heard through
// FleetWatch. The logic is the Dispatcher's, the memory the TaskStore's.
class ManagerNode {
 public:
  ManagerNode(dds::Participant& participant, TaskStore& store, TaskLimits limits,
              ManagerOptions options);
  // Until shutdown is requested; the exit code.
  int run();

 private:
  void on_request(const msg::ManagerRequest& request);
  // What a held submission waits for: `what` ("the fleet", "UGV 7") and the interim
  // answer's words.
  struct Wait {
    std::string what;
    std::string message;
  };
  // Why a submission must wait before it is judged: until the manager has listened for one
  // heartbeat timeout, then, up to restart_grace_s after its start, while the task names a
  // vehicle it listens to and has not heard yet (discovery can take seconds). nullopt:
  // judge it now.
  std::optional<Wait> why_wait(const msg::ManagerRequest& request, double now_s) const;
  // A submission: held with an interim answer while it must wait, else handled.
  void take_submission(const msg::ManagerRequest& request, double now_s);
  // Its index in held_, or held_.size() when it is not held.
  std::size_t held_position(const std::string& request_id) const;
  // The interim answer (ManagerReply.interim) to a held submission: what it waits for.
  void answer_interim(const msg::ManagerRequest& request, const std::string& why);
  void handle(const msg::ManagerRequest& request, double now_s);
  msg::ManagerReply submit(const msg::ManagerRequest& request, double now_s);
  void log_submission(const msg::ManagerRequest& request, const TaskStore::SubmitResult& result,
                      const SubmissionAnswer& answer) const;
  msg::ManagerReply abort(const msg::ManagerRequest& request, double now_s);
  msg::ManagerReply query(const msg::ManagerRequest& request) const;
  void step(double now_s);
  void send(const Actions& actions, double now_s);

  TaskStore& store_;
  Dispatcher dispatcher_;
  ManagerOptions options_;
  FleetWatch fleet_;
  dds::Writer<msg::ManagerReply> reply_writer_;
  dds::Writer<msg::TransitionTask> dispatch_writer_;
  dds::Writer<msg::TaskAbort> abort_writer_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<msg::ManagerRequest> requests_;
  // The replies to recent requests, by request id: a station re-sends until answered, and
  // a repeat gets the first answer instead of being carried out again.
  std::map<std::string, msg::ManagerReply> answered_;
  // Submissions are judged against the live fleet, which a manager that has just started
  // has not heard yet: they wait (why_wait) in held_, in submission order, each answered
  // at once with an interim reply and again when its station re-sends it.
  double listening_since_s_ = 0.0;
  double listen_first_s_ = 0.0;
  struct Held {
    msg::ManagerRequest request;
    Wait why;  // its interim answer, given again to each repeat
  };
  std::deque<Held> held_;
  std::deque<std::string> answered_order_;
  dds::Reader<msg::ManagerRequest> request_reader_;  // last: its callback uses the above
};

}  // namespace cover::task_manager
