#pragma once

#include <cstdint>
#include <string>

#include "cover/task_manager/task_state.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::task_manager {

// One task as the manager stores it. Times are wall clock (Unix seconds) given by the caller.
struct TaskRecord {
  std::string task_id;
  int uav_id = 0;
  std::int64_t queue_position = 0;  // submission order, strictly increasing per store
  TaskState state = TaskState::Queued;
  std::string submitter;
  std::string request_id;
  mission::Task task;
  double submitted_s = 0.0;
  double updated_s = 0.0;
  std::string reason;  // of the last state change
  // Queued at submission: the task holds its id for good, whatever becomes of it. False for
  // a submission rejected at once, which holds nothing: a new submission with its id
  // replaces it (TaskStore::submit), as a service keyed by client ids saves no result for
  // a request that failed validation.
  bool accepted = true;
};

// One row of a task's history; the submission is the first (from == to == initial state).
// A submission that replaced a rejected one under the same id follows that one's rows, from
// rejected to its own initial state.
struct StateChange {
  std::string task_id;
  TaskState from = TaskState::Queued;
  TaskState to = TaskState::Queued;
  double time_s = 0.0;
  std::string reason;
};

}  // namespace cover::task_manager
