#pragma once

#include <optional>

#include "cover/msg/types.hpp"
#include "cover/vocabulary/solve_status.hpp"

namespace cover::wire {

// SAMPC's outcome on the wire (enums.hpp's rules: an unknown wire value reads as nullopt).
// Apart from enums.hpp: only the UAV side and the simulator know the solver.
msg::SolverStatus to_msg(sampc::SolveStatus status);
std::optional<sampc::SolveStatus> from_msg(msg::SolverStatus status);

}  // namespace cover::wire
