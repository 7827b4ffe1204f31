#include "cover/task_manager/submission_answer.hpp"

#include <vector>

#include "cover/task_manager/task_difference.hpp"

namespace cover::task_manager {
namespace {

// A message names a few differences: enough to find the edit, short enough to read.
constexpr std::size_t kDifferencesNamed = 4;

std::string listed(const std::vector<std::string>& differences) {
  std::string text;
  for (std::size_t i = 0; i < differences.size() && i < kDifferencesNamed; ++i) {
    text += (i == 0 ? "" : ", ") + differences[i];
  }
  if (differences.size() > kDifferencesNamed) {
    text += " and " + std::to_string(differences.size() - kDifferencesNamed) + " more";
  }
  return text;
}

}  // namespace

std::string queued_message(int uav_id) {
  return "queued for UAV " + std::to_string(uav_id);
}

SubmissionAnswer answer_submission(const mission::Task& submitted,
                                   const TaskStore::SubmitResult& result) {
  const TaskRecord& r = result.record;
  if (result.created) {
    if (r.state == TaskState::Rejected) return {false, "rejected: " + r.reason};
    return {true, queued_message(r.uav_id)};
  }
  const std::vector<std::string> differences = task_differences(r.task, submitted);
  if (differences.empty()) return {true, queued_message(r.uav_id)};
  return {false, "task '" + r.task_id + "' is already known: " + to_string(r.state) +
                     (r.reason.empty() ? "" : " (" + r.reason + ")") +
                     "; this submission differs in " + listed(differences) +
                     " (submit it under another task_id)"};
}

}  // namespace cover::task_manager
