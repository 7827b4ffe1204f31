#pragma once

#include <cstdint>

namespace cover::mission {

// Where a task stands: what the UAV reports and the task manager follows.
enum class MissionState : std::uint8_t {
  NotStarted = 0,
  Running = 1,
  Complete = 2,
  Failed = 3,
  Aborted = 4,  // ended by the operator (StageMachine::abort)
};

// True once the task can no longer change state (complete, failed or aborted).
inline bool is_terminal(MissionState state) {
  return state == MissionState::Complete || state == MissionState::Failed ||
         state == MissionState::Aborted;
}

const char* to_string(MissionState state);

}  // namespace cover::mission
