#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cover/mission/mission_params.hpp"
#include "cover/vocabulary/mission_state.hpp"
#include "cover/vocabulary/stage.hpp"
#include "cover/vocabulary/stage_decision.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::mission {

// The stage machine of paper sec. 3.2: pure logic, no planner or MPC inside. Given the
// UAV's relative state in the current reference frame and the time, it decides stage,
// reference UGV, stage starts (replanning), final actions, timeouts and failures.
// Never throws after construction; every call is O(1) and allocation-free.
class StageMachine {
 public:
  // `task` must have passed Task::validate (the constructor throws ConfigError otherwise
  // via `params.validate()` only; the task is trusted here).
  StageMachine(Task task, MissionParams params);

  // The UGV whose frame the next `update` must be given the relative state in.
  int reference_ugv() const { return decision_.reference_ugv; }
  const StageDecision& decision() const { return decision_; }
  const Task& task() const { return task_; }
  const MissionParams& params() const { return params_; }

  // One control step. `position_m`, `velocity_m_s`: UAV relative to `reference_ugv()`,
  // in its frame. The first call starts process 0's initial stage. At most one stage
  // ends per call (the caller then switches to the new reference frame).
  const StageDecision& update(double time_s, const Eigen::Vector3d& position_m,
                              const Eigen::Vector3d& velocity_m_s);

  // Ends the mission with a failure the caller detected (stale inputs, planner failure).
  void fail(FailureReason reason, double time_s);
  // Ends the mission on the operator's request; false when it had already ended.
  bool abort(double time_s);

  // Human-readable one-line status, e.g. for a failure: which process, stage, why.
  std::string describe() const;

 private:
  void start_stage(std::size_t process_index, model::Stage stage, double time_s);
  void finish_final_stage(double time_s);
  bool reached(const Eigen::Vector3d& position_m, const Eigen::Vector3d& velocity_m_s) const;
  double timeout_s(model::Stage stage) const;
  const TransitionProcess& process() const { return task_.processes[decision_.process_index]; }

  Task task_;
  MissionParams params_;
  StageDecision decision_;
  double stage_start_s_ = 0.0;
  double last_distance_m_ = 0.0;  // distance to p_t(s) at the last update, for `describe`
};

}  // namespace cover::mission
