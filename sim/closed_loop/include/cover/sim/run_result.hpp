#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "cover/mission/stage_machine.hpp"
#include "cover/sim/approach_law.hpp"
#include "cover/sim/transition_bound.hpp"

namespace cover::sim {

// One transition stage as seen in the world frame (Table 1 and Fig. 8 metrics).
struct TransitionRecord {
  int process_index = 0;
  int from_ugv = 0;
  int to_ugv = 1;
  double start_time_s = 0.0;
  double end_time_s = 0.0;
  bool completed = false;  // the stage ended by reaching its point (not by the run ending)
  Eigen::Vector3d start_world_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d start_world_velocity_m_s = Eigen::Vector3d::Zero();
  double path_length_m = 0.0;      // L_t of this stage: UAV world path length
  double straight_length_m = 0.0;  // L_s of this stage: |end - start| in the world
  // The same start flown by the eq. 30 law with a perfect controller (approach_law.hpp).
  ApproachLawResult eq30_law;
  // The shortest path from the same start within the task's limits, arriving by this
  // stage's own end (transition_bound.hpp): no flight within the limits is shorter.
  TransitionBoundResult bound;
  // Over switch_window_s after the frame switch, per control step:
  double peak_rate_change_rad_s = 0.0;  // max |w_k - w_(k-1)| of the body-rate command
  double rms_rate_change_rad_s = 0.0;
  double peak_thrust_change_m_s2 = 0.0;  // max |F_k - F_(k-1)|
  double peak_world_speed_m_s = 0.0;     // max UAV world speed
};

struct StagedPoint {
  Eigen::Vector2d uav_world_m = Eigen::Vector2d::Zero();
  int stage_code = -1;  // cover::model::Stage as int; -1 before start / after the end
};

// One control step as the controller saw it and as it was (ClosedLoopOptions::
// record_step_trace): what a tracking error over time is read from.
struct StepSample {
  double time_s = 0.0;
  int stage_code = -1;  // cover::model::Stage as int; -1 when not running
  int process_index = 0;
  int reference_ugv = 0;
  // True relative state in the reference UGV's frame, and the reference position there.
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d reference_position_m = Eigen::Vector3d::Zero();
  double thrust_m_s2 = 0.0;
  Eigen::Vector3d body_rate_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d disturbance_m_s2 = Eigen::Vector3d::Zero();
};

struct ClosedLoopResult {
  bool success = false;
  std::string status;  // the stage machine's last status line (names the failure)
  mission::MissionState mission_state = mission::MissionState::NotStarted;
  double duration_s = 0.0;   // simulated time until the task completed (or the run ended)
  double wall_time_s = 0.0;  // wall-clock time of the whole run
  double realtime_factor = 0.0;

  std::vector<TransitionRecord> transitions;
  double total_path_length_m = 0.0;      // L_t, summed over completed transition stages
  double total_straight_length_m = 0.0;  // L_s, summed over completed transition stages
  // The same sums for the eq. 30 law flown from the same starts (approach_law.hpp).
  double eq30_law_path_length_m = 0.0;
  double eq30_law_straight_length_m = 0.0;
  // ... and for the bound, over the completed transitions whose bound was reached.
  double bound_path_length_m = 0.0;
  double bound_straight_length_m = 0.0;

  // Mean absolute error per axis of the UAV (true relative position) to the reference
  // trajectory in the final stages, in the reference frame. NaN if no final stage ran.
  Eigen::Vector3d final_tracking_error_m = Eigen::Vector3d::Constant(std::nan(""));
  int final_tracking_samples = 0;
  // Horizontal distance on the target deck from the landing / delivery point (NaN if the
  // task has no such action or it did not happen).
  double landing_error_m = std::nan("");
  bool landed_on_target_deck = false;
  double delivery_error_m = std::nan("");

  // Controller timing (medians / p99 over the run). NaN: not measured (JSON null, "not
  // measured" in the summary, never 0). As processes, the UAV agent's trace carries each
  // SAMPC step's wall time and each plan's time, but not SAMPC's thread CPU time, and
  // cover-sim does not run the control step: those stay NaN.
  double mpc_median_us = std::nan("");
  double mpc_p99_us = std::nan("");
  // The same in the control thread's CPU time: what SAMPC costs without preemption by
  // other processes (which dominates the wall-clock p99 on a loaded machine).
  double mpc_cpu_median_us = std::nan("");
  double mpc_cpu_p99_us = std::nan("");
  // Measurement -> command of the steps SAMPC flew (wall, ControllerStatus::command_us): the
  // feedback phase and the loop around it when the step was prepared ahead (in process and
  // from the UAV agent's trace alike).
  double command_median_us = std::nan("");
  double command_p99_us = std::nan("");
  double plan_median_ms = std::nan("");
  double plan_max_ms = std::nan("");
  // Wall time of each whole control step (UavLoop::step: inputs, stage machine, SAMPC,
  // and the wait for a plan due at that step; nothing excluded), and the longest such wait
  // (in process only: ClosedLoop).
  double step_median_us = std::nan("");
  double step_p99_us = std::nan("");
  double step_max_us = std::nan("");
  double plan_wait_max_ms = std::nan("");
  int failsafe_steps = 0;  // control steps whose command was a failsafe (stale/solver)

  // Every control step of the run, when ClosedLoopOptions::record_step_trace.
  std::vector<StepSample> step_trace;

  // World-frame paths for plots (decimated).
  std::vector<StagedPoint> uav_path;
  std::vector<std::vector<Eigen::Vector2d>> ugv_paths;
  std::vector<Eigen::Vector2d> release_points;
  std::vector<Eigen::Vector2d> landing_points;
};

}  // namespace cover::sim
