#pragma once

#include <string>

#include "cover/task_manager/task_store.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::task_manager {

// What the manager answers a submission, from what the store made of it.
struct SubmissionAnswer {
  bool ok = false;
  std::string message;
};

// Created: "queued for UAV <u>" (ok), or "rejected: <reason>". The id of a task accepted
// before: with the same content (task_differences empty), the first answer again, "queued
// for UAV <u>" (ok: a station that lost the answer may submit again); with other content,
// refused, naming the known task's state and reason and what differs:
// "task 'hop' is already known: running (UAV 0 runs it); this submission differs in
// processes[0].to_ugv 1 -> 7 (submit it under another task_id)".
SubmissionAnswer answer_submission(const mission::Task& submitted,
                                   const TaskStore::SubmitResult& result);

// "queued for UAV <u>": the answer that accepted a task.
std::string queued_message(int uav_id);

}  // namespace cover::task_manager
