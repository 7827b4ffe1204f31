#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace cover::task_manager {

// A task's state in the manager (not the agent's view of it, see AgentReport).
// Stored as text (to_string) so the database reads well and survives enum reordering.
enum class TaskState : std::uint8_t {
  Queued,      // accepted, waiting for its UAV
  Dispatched,  // sent to the UAV agent, not yet taken
  Running,     // the agent flies it
  Succeeded,
  Failed,
  Aborted,
  Rejected,  // refused at submission (manager) or by the agent
};

// "queued", "dispatched", "running", "succeeded", "failed", "aborted", "rejected".
const char* to_string(TaskState state);
std::optional<TaskState> parse_task_state(std::string_view text);

// Succeeded, Failed, Aborted and Rejected: nothing changes a task once there.
bool is_final(TaskState state);

}  // namespace cover::task_manager
