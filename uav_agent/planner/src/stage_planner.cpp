#include "cover/planner/stage_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "cover/planner/lbfgs.hpp"
#include "cover/planner/stage_objective.hpp"

namespace cover::planner {

namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

// Peak speed and acceleration of the rest-to-rest minimum-jerk profile over distance D in
// time T are 1.875 D/T and 5.774 D/T^2: the shortest T that respects both is a safe guess.
double rest_to_rest_duration(double distance_m, double vmax_m_s, double amax_m_s2) {
  return std::max(1.875 * distance_m / vmax_m_s, std::sqrt(5.774 * distance_m / amax_m_s2));
}

// Where the start velocity alone carries the UAV by time t when it brakes at `decel`: the
// initial guess bends by this much, never more than the braking distance. (Bending by
// v0 t would start long stages with a multi-metre detour, from which L-BFGS settles in a
// wobbly local minimum: a 7.2 m transition planned as 14.6 s instead of about 8.)
Eigen::Vector3d braking_offset(const Eigen::Vector3d& v0, double decel, double t) {
  const double speed = v0.norm();
  if (speed <= 0.0 || decel <= 0.0) return Eigen::Vector3d::Zero();
  const double tau = std::min(t, speed / decel);
  return v0 * (tau - 0.5 * decel / speed * tau * tau);
}

// Minimum-jerk blend 10u^3 - 15u^4 + 6u^5: position fraction at time fraction u.
double min_jerk_fraction(double u) {
  return u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}

}  // namespace

// Everything one plan needs, sized at construction: plan() allocates nothing.
struct StagePlanner::Optimiser {
  explicit Optimiser(const PlannerParams& params)
      : objective(params),
        x(objective.dimension()),
        guess(objective.dimension()),
        gradient(objective.dimension()),
        durations(params.pieces),
        waypoints(3, params.pieces - 1) {
    lbfgs.resize(objective.dimension(), params.lbfgs_memory);
    settings.memory = params.lbfgs_memory;
    settings.relative_cost_tolerance = params.relative_cost_tolerance;
    settings.relative_step_tolerance = params.relative_step_tolerance;
    settings.max_evaluations = params.max_evaluations;
    settings.max_solve_time_s = params.max_solve_time_s;
  }

  static double callback(const double* x, double* gradient, void* data) {
    return static_cast<Optimiser*>(data)->objective.evaluate(x, gradient);
  }

  StageObjective objective;
  Lbfgs lbfgs;
  LbfgsSettings settings;
  Eigen::VectorXd x, guess, gradient;
  Eigen::VectorXd durations;
  Eigen::Matrix3Xd waypoints;
};

StagePlanner::StagePlanner(PlannerParams params) : params_(std::move(params)) {
  params_.validate();
  optimiser_ = std::make_unique<Optimiser>(params_);
}

StagePlanner::~StagePlanner() = default;
StagePlanner::StagePlanner(StagePlanner&&) noexcept = default;
StagePlanner& StagePlanner::operator=(StagePlanner&&) noexcept = default;

const char* StagePlanner::problem_error(const StageProblem& problem) const {
  const auto bad_vector = [](const Eigen::Vector3d& v, double bound) {
    return !v.allFinite() || v.cwiseAbs().maxCoeff() > bound;
  };
  if (bad_vector(problem.start_position_m, params_.max_abs_position_m))
    return "start position is not finite or beyond max_abs_position_m";
  if (bad_vector(problem.goal_position_m, params_.max_abs_position_m))
    return "goal position is not finite or beyond max_abs_position_m";
  if (bad_vector(problem.start_velocity_m_s, params_.max_abs_speed_m_s))
    return "start velocity is not finite or beyond max_abs_speed_m_s";
  if (problem.transition_stage &&
      bad_vector(problem.ugv_angular_velocity_rad_s, params_.max_abs_angular_rate_rad_s))
    return "UGV angular velocity is not finite or beyond max_abs_angular_rate_rad_s";
  if (!std::isfinite(problem.vmax_m_s) || problem.vmax_m_s <= 0.0 ||
      problem.vmax_m_s > params_.max_limit_m_s)
    return "vmax must be finite, > 0 and <= max_limit_m_s (is vmax_uav <= vmax_ugv? eq. 15)";
  if (!std::isfinite(problem.amax_m_s2) || problem.amax_m_s2 <= 0.0 ||
      problem.amax_m_s2 > params_.max_limit_m_s2)
    return "amax must be finite, > 0 and <= max_limit_m_s2 (is amax_uav <= amax_ugv? eq. 15)";
  if (!problem.transition_stage && !problem.start_acceleration_m_s2.allFinite())
    return "start acceleration is not finite";
  if (bad_vector(initial_velocity(problem), params_.max_abs_speed_m_s))
    return "eq. 23 initial velocity v + Omega x p exceeds max_abs_speed_m_s";
  return nullptr;
}

std::string StagePlanner::check_problem(const StageProblem& problem) const {
  const char* error = problem_error(problem);
  return error == nullptr ? std::string() : std::string(error);
}

PlanResult StagePlanner::plan(const StageProblem& problem) noexcept {
  PlanResult result;
  plan(problem, result);
  return result;
}

void StagePlanner::plan(const StageProblem& problem, PlanResult& result) noexcept {
  const auto started = Clock::now();
  try {
    plan_or_throw(problem, result);
  } catch (...) {
    // Only allocation failure (a first trajectory into `result`) can get here; hold the
    // start if it is sane.
    result.status = PlanStatus::Failed;
    result.reason = "internal error (allocation failure)";
    const bool start_ok = problem.start_position_m.allFinite();
    try {
      result.trajectory.assign_hold(start_ok ? problem.start_position_m : Eigen::Vector3d::Zero());
    } catch (...) {
      result.trajectory = Trajectory();  // keeps its one piece: holds the origin
    }
  }
  result.solve_ms = elapsed_ms(started);
}

namespace {

// Why L-BFGS stopped, as a plan status and reason.
void classify(LbfgsResult why, bool improved, PlanResult& result) {
  switch (why) {
    case LbfgsResult::CostConverged:
    case LbfgsResult::StepConverged:
      result.status = PlanStatus::Ok;
      result.reason = "converged";
      return;
    case LbfgsResult::RoundoffLimited:
      // No step along the search direction lowers the cost in floating point: at the
      // optimum for all practical purposes.
      result.status = PlanStatus::Ok;
      result.reason = "converged to rounding precision";
      return;
    case LbfgsResult::MaxEvaluations:
      result.status = PlanStatus::EarlyStop;
      result.reason = "stopped at max_evaluations";
      return;
    case LbfgsResult::MaxTime:
      result.status = PlanStatus::EarlyStop;
      result.reason = "stopped at max_solve_time_s";
      return;
    case LbfgsResult::LineSearchFailed:
      break;
  }
  result.status = improved ? PlanStatus::EarlyStop : PlanStatus::Failed;
  result.reason = improved
                      ? "L-BFGS broke down; keeping the best point it evaluated"
                      : "L-BFGS broke down at the initial guess; flying the safe initial guess";
}

}  // namespace

void StagePlanner::plan_or_throw(const StageProblem& problem, PlanResult& result) {
  result.iterations = 0;
  result.initial_velocity_m_s.setZero();
  if (const char* error = problem_error(problem)) {
    result.status = PlanStatus::InvalidInput;
    result.reason = error;
    // Holding the start is the least surprising reference; with no finite start, the
    // origin of the frame (the UGV itself would be wrong to fly to, so callers must
    // treat InvalidInput as "do not follow" and keep hovering).
    const bool start_ok = problem.start_position_m.allFinite();
    result.trajectory.assign_hold(start_ok ? problem.start_position_m : Eigen::Vector3d::Zero());
    return;
  }

  const Eigen::Vector3d v0 = initial_velocity(problem);
  const Eigen::Vector3d a0 = initial_acceleration(problem);
  result.initial_velocity_m_s = v0;
  const double distance = (problem.goal_position_m - problem.start_position_m).norm();
  if (distance <= params_.at_goal_tolerance_m && v0.norm() <= params_.at_rest_tolerance_m_s &&
      a0.isZero()) {
    result.status = PlanStatus::Ok;
    result.reason = "already at the goal and at rest: hold";
    result.trajectory.assign_hold(problem.start_position_m);
    return;
  }

  const double guess_cost = prepare_guess(problem, v0, a0);
  Optimiser& optimiser = *optimiser_;
  optimiser.x = optimiser.guess;
  double final_cost = 0.0;
  int evaluations = 0;
  const LbfgsResult why =
      optimiser.lbfgs.minimize(&Optimiser::callback, &optimiser, optimiser.settings,
                               optimiser.x.data(), final_cost, evaluations);
  result.iterations = evaluations;
  write_result(why, guess_cost, problem.start_position_m, result);
}

// Initial guess (paper: uniform front-end path between p0 and p_t): the rest-to-rest
// minimum-jerk profile with a safe duration, plus time to absorb v0, bent by v0 so the
// first piece agrees with the start velocity. Also the fallback if L-BFGS breaks down.
// The cost is scaled to a unit gradient at the guess (L-BFGS's first step is unit
// length); returns the guess's scaled cost.
double StagePlanner::prepare_guess(const StageProblem& problem, const Eigen::Vector3d& v0,
                                   const Eigen::Vector3d& a0) {
  const Eigen::Vector3d start = problem.start_position_m;
  const Eigen::Vector3d displacement = problem.goal_position_m - start;
  const double vm = problem.vmax_m_s;
  const double am = problem.amax_m_s2;
  Optimiser& optimiser = *optimiser_;
  const int pieces = params_.pieces;
  const double stop_time = 2.0 * v0.norm() / am;
  const double total_time =
      std::max(rest_to_rest_duration(displacement.norm(), vm, am) + stop_time, 1.0e-2);
  optimiser.durations.setConstant(total_time / pieces);
  for (int i = 1; i < pieces; ++i) {
    const double u = static_cast<double>(i) / pieces;
    const double t = u * total_time;
    optimiser.waypoints.col(i - 1) = start + min_jerk_fraction(u) * displacement +
                                     braking_offset(v0, 0.5 * am, t) * (1.0 - u) * (1.0 - u);
  }

  StageObjective& objective = optimiser.objective;
  objective.set_problem(start, v0, a0, problem.goal_position_m, vm, am);
  objective.encode(optimiser.waypoints, optimiser.durations, optimiser.guess.data());
  const double guess_unscaled =
      objective.evaluate(optimiser.guess.data(), optimiser.gradient.data());
  const double gradient_norm = optimiser.gradient.norm();
  if (std::isfinite(gradient_norm) && gradient_norm > 1.0) {
    objective.set_cost_scale(1.0 / gradient_norm);
  }
  objective.reset_tracking();
  return guess_unscaled * objective.cost_scale();
}

// The best point L-BFGS evaluated (the last accepted iterate is one, every accepted step
// lowering the cost, but the objective tracks the best anyway), else the guess, else a
// hold at the start: never a trajectory that is not finite.
void StagePlanner::write_result(LbfgsResult why, double guess_cost, const Eigen::Vector3d& start,
                                PlanResult& result) {
  Optimiser& optimiser = *optimiser_;
  StageObjective& objective = optimiser.objective;
  const bool have_best = StageObjective::is_usable_cost(objective.best_cost());
  const double* best = have_best ? objective.best_x().data() : optimiser.guess.data();
  classify(why, have_best && objective.best_cost() < guess_cost, result);

  if (result.status != PlanStatus::Failed) {
    objective.write_trajectory(best, result.trajectory);
    if (result.trajectory.is_finite()) return;
    result.status = PlanStatus::Failed;
    result.reason = "optimised trajectory was not finite; flying the safe initial guess";
  }
  objective.write_trajectory(optimiser.guess.data(), result.trajectory);
  if (!result.trajectory.is_finite()) {
    result.reason = "initial guess was not finite; holding the start";
    result.trajectory.assign_hold(start);
  }
}

}  // namespace cover::planner
