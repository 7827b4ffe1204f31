#pragma once

#include <Eigen/Core>
#include <cstddef>

#include "cover/vocabulary/failure_reason.hpp"
#include "cover/vocabulary/mission_state.hpp"
#include "cover/vocabulary/stage.hpp"

namespace cover::mission {

// What the stage machine decided at one control step. Everything the controller needs to
// act: which frame to fly in, where to go, whether to plan now, and the final actions.
struct StageDecision {
  MissionState state = MissionState::NotStarted;
  FailureReason failure = FailureReason::None;
  std::size_t process_index = 0;
  model::Stage stage = model::Stage::Initial;
  int reference_ugv = 0;                                     // frame of the stage (Gi or Gj)
  Eigen::Vector3d target_point_m = Eigen::Vector3d::Zero();  // p_t(s), in that frame
  double stage_time_s = 0.0;      // t of the paper: reset to 0 at each stage start
  bool stage_started = false;     // a stage began this step: (re)plan its reference now
  bool armed = true;              // false once the landing point is reached (latched)
  bool release_payload = false;   // true on the one step the delivery point is reached
  bool payload_released = false;  // latched once any delivery happened
};

}  // namespace cover::mission
