#pragma once

#include <cstdint>

#include "cover/msg/types.hpp"
#include "cover/planner/trajectory.hpp"
#include "cover/vocabulary/stage.hpp"

namespace cover::wire {

// A stage's reference for display: z(t) sampled every `dt_s` over its duration (at most
// `max_samples`, so a long stage is sampled coarser rather than truncated), in
// G_reference_ugv, stamped with the stage start.
msg::ReferenceTrajectory to_reference(const planner::Trajectory& trajectory, std::uint32_t uav_id,
                                      double stage_start_s, int reference_ugv, model::Stage stage,
                                      double dt_s = 0.05, int max_samples = 1000);

}  // namespace cover::wire
