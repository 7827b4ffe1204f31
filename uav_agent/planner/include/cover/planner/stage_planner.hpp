#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "cover/planner/planner_params.hpp"
#include "cover/planner/stage_problem.hpp"
#include "cover/planner/trajectory.hpp"
#include "cover/vocabulary/plan_status.hpp"

namespace cover::planner {

enum class LbfgsResult;  // lbfgs.hpp

struct PlanResult {
  PlanStatus status = PlanStatus::Failed;
  const char* reason = "";  // static string: why this status
  // Always finite and usable as a reference, whatever the status (see PlanStatus).
  Trajectory trajectory;
  // The v0(s) actually used (after eq. 23 at the transition stage).
  Eigen::Vector3d initial_velocity_m_s = Eigen::Vector3d::Zero();
  // Cost evaluations (value + gradient) spent by L-BFGS, the initial guess's included.
  int iterations = 0;
  double solve_ms = 0.0;
};

// Plans one stage (paper sec. 4.2): MINCO minimum jerk with free waypoints and durations,
// cost integral ||jerk||^2 + rho T + velocity/acceleration penalties, L-BFGS (lbfgs.hpp).
// Start (p0, v0, a0), end (p_t, 0, 0). plan() never throws and never returns NaN.
// One planner owns one workspace, sized at construction: not thread-safe, reuse it across
// stages. plan(problem, result) allocates nothing once `result` has held a plan (its
// trajectory's storage is reused); plan(problem) returns a fresh result.
class StagePlanner {
 public:
  // Throws config::ConfigError when params are invalid (at construction, not in the loop).
  explicit StagePlanner(PlannerParams params);
  ~StagePlanner();
  StagePlanner(StagePlanner&&) noexcept;
  StagePlanner& operator=(StagePlanner&&) noexcept;
  StagePlanner(const StagePlanner&) = delete;
  StagePlanner& operator=(const StagePlanner&) = delete;

  PlanResult plan(const StageProblem& problem) noexcept;
  void plan(const StageProblem& problem, PlanResult& result) noexcept;
  const PlannerParams& params() const { return params_; }

  // Empty when the problem is acceptable, else the reason it is not.
  std::string check_problem(const StageProblem& problem) const;
  // The same as a static string, nullptr when acceptable.
  const char* problem_error(const StageProblem& problem) const;

 private:
  struct Optimiser;
  void plan_or_throw(const StageProblem& problem, PlanResult& result);
  double prepare_guess(const StageProblem& problem, const Eigen::Vector3d& v0,
                       const Eigen::Vector3d& a0);
  void write_result(LbfgsResult why, double guess_cost, const Eigen::Vector3d& start,
                    PlanResult& result);

  PlannerParams params_;
  std::unique_ptr<Optimiser> optimiser_;
};

}  // namespace cover::planner
