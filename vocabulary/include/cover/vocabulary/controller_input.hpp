#pragma once

#include "cover/vocabulary/relative_state.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::mission {

// The UAV loop's inputs, one of each per UGV: what the UAV agent's DDS intake and the
// simulator hand the mission controller.

// The UAV's state relative to one UGV, in that UGV's frame G_k (from the relative
// estimator; the DDS adapter or the simulator fills it).
using RelativeMeasurement = model::RelativeState;

// The filtered IMU of one UGV (a, Omega, beta in G_k), as its agent publishes it.
struct UgvImuMeasurement {
  double stamp_s = 0.0;
  model::UgvMotion motion;
};

}  // namespace cover::mission
