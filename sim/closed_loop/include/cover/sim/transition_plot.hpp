#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "cover/sim/run_result.hpp"

namespace cover::sim {

// One transition stage of a run, in the world frame: what the UAV flew, what its target
// UGV drove meanwhile, and the shortest path within the limits (the bound).
struct TransitionTrace {
  std::string label;  // e.g. the method
  std::vector<Eigen::Vector2d> uav_m;
  std::vector<Eigen::Vector2d> target_m;
  std::vector<Eigen::Vector2d> bound_m;
};

// Transition `index` (0: the run's first) of a run recorded with record_paths: its
// stretch of the decimated UAV path and of the target UGV's. Empty paths if the run has no
// such transition or did not record paths.
TransitionTrace transition_trace(const ClosedLoopResult& result, std::size_t index,
                                 const std::string& label);

// A Fig. 7b-like top view: one transition per trace, each in its own colour (UAV solid,
// its target UGV dashed), the bounds thin grey dashed. False if not writable.
bool write_transitions_plot(const std::vector<TransitionTrace>& traces, const std::string& title,
                            const std::string& path);

}  // namespace cover::sim
