#include "cover/task_manager/task_state.hpp"

#include <array>

namespace cover::task_manager {
namespace {
constexpr std::array<TaskState, 7> kAllStates = {
    TaskState::Queued, TaskState::Dispatched, TaskState::Running, TaskState::Succeeded,
    TaskState::Failed, TaskState::Aborted,    TaskState::Rejected};
}  // namespace

const char* to_string(TaskState state) {
  switch (state) {
    case TaskState::Queued:
      return "queued";
    case TaskState::Dispatched:
      return "dispatched";
    case TaskState::Running:
      return "running";
    case TaskState::Succeeded:
      return "succeeded";
    case TaskState::Failed:
      return "failed";
    case TaskState::Aborted:
      return "aborted";
    case TaskState::Rejected:
      return "rejected";
  }
  return "unknown";
}

std::optional<TaskState> parse_task_state(std::string_view text) {
  for (const TaskState state : kAllStates) {
    if (text == to_string(state)) return state;
  }
  return std::nullopt;
}

bool is_final(TaskState state) {
  return state == TaskState::Succeeded || state == TaskState::Failed ||
         state == TaskState::Aborted || state == TaskState::Rejected;
}

}  // namespace cover::task_manager
