#pragma once

#include <Eigen/Core>

#include "cover/vocabulary/control_command.hpp"
#include "cover/vocabulary/failsafe.hpp"
#include "cover/vocabulary/failsafe_cause.hpp"
#include "cover/vocabulary/plan_status.hpp"
#include "cover/vocabulary/solve_status.hpp"
#include "cover/vocabulary/stage_decision.hpp"

namespace cover::mission {

// What the UAV loop returns every step: the command and why it is what it is (published as
// the command, the trace and the status).
struct ControllerStatus {
  StageDecision stage;  // stage, process, reference UGV, mission state, failure reason
  Failsafe failsafe = Failsafe::WaitingForInputs;
  // Why the failsafe ladder was last climbed, and how old that input was then (s).
  FailsafeCause failsafe_cause = FailsafeCause::None;
  double failsafe_input_age_s = 0.0;
  sampc::SolveStatus solve_status = sampc::SolveStatus::Ok;
  double solve_us = 0.0;      // SAMPC time of this step (wall clock)
  double solve_cpu_us = 0.0;  // the same in this thread's CPU time (preemption excluded)
  // SAMPC's feedback phase of this step (part of solve_us; the rest, the preparation, ran
  // after the previous command when this step's was prepared ahead).
  double feedback_us = 0.0;
  // Wall time from the step taking its measurements to its command: what a measurement
  // waits for its command (the feedback phase and the loop around it; 0: not measured).
  double command_us = 0.0;
  bool planned = false;  // a stage reference was adopted this step (planned off-thread)
  planner::PlanStatus plan_status = planner::PlanStatus::Ok;  // of the last plan
  double plan_ms = 0.0;                                       // of the last plan (worker)
  // Of the last plan: how long this thread waited for it at its adoption step (lockstep; 0
  // when it was ready), and how many steps after that step it was adopted (realtime).
  double plan_wait_ms = 0.0;
  int plan_late_steps = 0;
  // Reference trajectory z(s, t) now, in the reference frame (for tracking metrics).
  Eigen::Vector3d reference_position_m = Eigen::Vector3d::Zero();
  // Estimate of the unmodelled acceleration (mass, drag) fed to SAMPC, m/s^2: the
  // observer's part plus the tracking-error integral's.
  Eigen::Vector3d disturbance_m_s2 = Eigen::Vector3d::Zero();
};

struct ControllerOutput {
  ControlCommand command;
  ControllerStatus status;
};

}  // namespace cover::mission
