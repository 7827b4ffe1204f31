#pragma once

#include <optional>

#include "cover/msg/types.hpp"
#include "cover/vocabulary/failsafe.hpp"
#include "cover/vocabulary/final_action.hpp"
#include "cover/vocabulary/mission_state.hpp"
#include "cover/vocabulary/stage.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::wire {

// Library enum -> wire enum, and back. A wire value the library has no counterpart for
// (an out-of-range number from a foreign writer, STAGE_IDLE, TASK_REJECTED) reads as
// nullopt: the caller decides what is safe.
msg::Stage to_msg(model::Stage stage, mission::MissionState state);  // IDLE before a task starts
std::optional<model::Stage> from_msg(msg::Stage stage);

msg::TaskState to_msg(mission::MissionState state);
std::optional<mission::MissionState> from_msg(msg::TaskState state);

msg::FailsafeState to_msg(mission::Failsafe failsafe);
std::optional<mission::Failsafe> from_msg(msg::FailsafeState failsafe);

msg::FinalAction to_msg(mission::FinalAction action);
std::optional<mission::FinalAction> from_msg(msg::FinalAction action);

msg::SpeedSource to_msg(model::SpeedSource source);
std::optional<model::SpeedSource> from_msg(msg::SpeedSource source);

}  // namespace cover::wire
