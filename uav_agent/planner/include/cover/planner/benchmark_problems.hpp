#pragma once

#include <cstdint>
#include <vector>

#include "cover/planner/stage_problem.hpp"

namespace cover::planner {

// A fixed, seeded set of stage problems like the paper's (sec. 5): goal at a transition
// point height, start within 8 m of it, initial speed up to 2 m/s (v0 after eq. 23),
// vmax in [1.0, 1.5] m/s, amax in [1.5, 3] m/s^2; every third problem is a transition
// stage with a UGV yaw rate up to 0.5 rad/s. Shared by cover-bench and the tests.
std::vector<StageProblem> make_benchmark_problems(int count, std::uint32_t seed = 2026);

}  // namespace cover::planner
