#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cover/mission/mission_params.hpp"
#include "cover/mission/mission_state.hpp"
#include "cover/mission/task.hpp"
#include "cover/model/stage.hpp"

namespace cover::mission {

enum class FailureReason : std::uint8_t {
  None = 0,
  StageTimeout = 1,      // a stage did not end within its timeout
  InvalidState = 2,      // NaN / infinite relative state
  StaleInput = 3,        // relative state or UGV IMU too old for too long
  PlanningFailed = 4,    // the reference trajectory could not be generated
  AutopilotControl = 5,  // the flight controller left COVER's mode (a pilot took over, its
                         // own failsafe) or its link was lost
};

const char* to_string(FailureReason reason);

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
