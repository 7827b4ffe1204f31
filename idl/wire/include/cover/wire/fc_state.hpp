#pragma once

#include <optional>
#include <string>

#include "cover/msg/types.hpp"

namespace cover::wire {

// Why the autopilot a flight-controller bridge reports is not flying COVER's setpoints
// (link down, not in OFFBOARD / GUIDED_NOGPS, disarmed), in words a person understands;
// nullopt when it is (FcState.offboard_ready). One wording for the UAV agent's task
// failures and the task manager's waiting reasons.
std::optional<std::string> fc_not_ready_reason(const msg::FcState& state);

}  // namespace cover::wire
