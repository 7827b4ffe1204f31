#include "cover/planner/stage_planner.hpp"

#include <nlopt.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "cover/planner/stage_objective.hpp"

namespace cover::planner {

namespace {

using Clock = std::chrono::steady_clock;

// Restarts of L-BFGS after a line-search failure, within the same evaluation budget.
constexpr int kMaxRestarts = 2;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

struct NloptDeleter {
  void operator()(nlopt_opt opt) const { nlopt_destroy(opt); }
};

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

struct StagePlanner::Optimiser {
  explicit Optimiser(const PlannerParams& params)
      : objective(params),
        opt(nlopt_create(NLOPT_LD_LBFGS, static_cast<unsigned>(objective.dimension()))),
        x(static_cast<std::size_t>(objective.dimension()), 0.0),
        gradient(x.size(), 0.0) {}

  static double callback(unsigned n, const double* x, double* gradient, void* data) {
    return static_cast<Optimiser*>(data)->objective.evaluate(x, gradient);
  }

  StageObjective objective;
  std::unique_ptr<nlopt_opt_s, NloptDeleter> opt;
  std::vector<double> x;
  std::vector<double> gradient;
};

StagePlanner::StagePlanner(PlannerParams params) : params_(std::move(params)) {
  params_.validate();
  optimiser_ = std::make_unique<Optimiser>(params_);
  nlopt_opt opt = optimiser_->opt.get();
  if (opt == nullptr) throw config::ConfigError("planner: NLopt could not create LD_LBFGS");
  nlopt_set_min_objective(opt, &Optimiser::callback, optimiser_.get());
  nlopt_set_ftol_rel(opt, params_.relative_cost_tolerance);
  nlopt_set_xtol_rel(opt, params_.relative_step_tolerance);
  nlopt_set_maxeval(opt, params_.max_evaluations);
  nlopt_set_maxtime(opt, params_.max_solve_time_s);
  nlopt_set_vector_storage(opt, static_cast<unsigned>(params_.lbfgs_memory));
}

StagePlanner::~StagePlanner() = default;
StagePlanner::StagePlanner(StagePlanner&&) noexcept = default;
StagePlanner& StagePlanner::operator=(StagePlanner&&) noexcept = default;

std::string StagePlanner::check_problem(const StageProblem& problem) const {
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
  return {};
}

PlanResult StagePlanner::plan(const StageProblem& problem) noexcept {
  const auto started = Clock::now();
  try {
    PlanResult result = plan_or_throw(problem);
    result.solve_ms = elapsed_ms(started);
    return result;
  } catch (...) {
    // Only allocation failure can get here; hold the start if it is sane.
    PlanResult result;
    result.status = PlanStatus::Failed;
    result.reason = "internal error (allocation failure)";
    const bool start_ok = problem.start_position_m.allFinite();
    result.trajectory =
        Trajectory::hold(start_ok ? problem.start_position_m : Eigen::Vector3d::Zero());
    result.solve_ms = elapsed_ms(started);
    return result;
  }
}

PlanResult StagePlanner::plan_or_throw(const StageProblem& problem) {
  PlanResult result;
  if (std::string reason = check_problem(problem); !reason.empty()) {
    result.status = PlanStatus::InvalidInput;
    result.reason = std::move(reason);
    // Holding the start is the least surprising reference; with no finite start, the
    // origin of the frame (the UGV itself would be wrong to fly to, so callers must
    // treat InvalidInput as "do not follow" and keep hovering).
    const bool start_ok = problem.start_position_m.allFinite();
    result.trajectory =
        Trajectory::hold(start_ok ? problem.start_position_m : Eigen::Vector3d::Zero());
    return result;
  }

  const Eigen::Vector3d start = problem.start_position_m;
  const Eigen::Vector3d goal = problem.goal_position_m;
  const Eigen::Vector3d v0 = initial_velocity(problem);
  const Eigen::Vector3d a0 = initial_acceleration(problem);
  const double vm = problem.vmax_m_s;
  const double am = problem.amax_m_s2;
  result.initial_velocity_m_s = v0;

  const Eigen::Vector3d displacement = goal - start;
  const double distance = displacement.norm();
  if (distance <= params_.at_goal_tolerance_m && v0.norm() <= params_.at_rest_tolerance_m_s &&
      a0.isZero()) {
    result.status = PlanStatus::Ok;
    result.reason = "already at the goal and at rest: hold";
    result.trajectory = Trajectory::hold(start);
    return result;
  }

  // Initial guess (paper: uniform front-end path between p0 and p_t): the rest-to-rest
  // minimum-jerk profile with a safe duration, plus time to absorb v0, bent by v0 so the
  // first piece agrees with the start velocity. Also the fallback if L-BFGS breaks down.
  const int pieces = params_.pieces;
  const double stop_time = 2.0 * v0.norm() / am;
  const double total_time = std::max(rest_to_rest_duration(distance, vm, am) + stop_time, 1.0e-2);
  Eigen::VectorXd durations = Eigen::VectorXd::Constant(pieces, total_time / pieces);
  Eigen::Matrix3Xd waypoints(3, pieces - 1);
  for (int i = 1; i < pieces; ++i) {
    const double u = static_cast<double>(i) / pieces;
    const double t = u * total_time;
    waypoints.col(i - 1) = start + min_jerk_fraction(u) * displacement +
                           braking_offset(v0, 0.5 * am, t) * (1.0 - u) * (1.0 - u);
  }

  Optimiser& optimiser = *optimiser_;
  StageObjective& objective = optimiser.objective;
  objective.set_problem(start, v0, a0, goal, vm, am);
  objective.encode(waypoints, durations, optimiser.x.data());
  const std::vector<double> guess = optimiser.x;
  std::vector<double>& gradient = optimiser.gradient;
  objective.evaluate(guess.data(), gradient.data());
  const double gradient_norm =
      Eigen::Map<const Eigen::VectorXd>(gradient.data(), objective.dimension()).norm();
  if (std::isfinite(gradient_norm) && gradient_norm > 1.0) {
    objective.set_cost_scale(1.0 / gradient_norm);
  }
  const double guess_cost = objective.evaluate(guess.data(), nullptr);
  objective.reset_tracking();

  // Luksan's line search occasionally gives up (NLOPT_FAILURE) on long, badly scaled
  // stages; restarting from the best point (fresh curvature memory) usually finishes.
  nlopt_result code = NLOPT_FAILURE;
  for (int attempt = 0; attempt <= kMaxRestarts; ++attempt) {
    const int remaining = params_.max_evaluations - objective.evaluations();
    if (remaining <= 0) break;
    if (attempt > 0) {
      std::copy(objective.best_x().data(), objective.best_x().data() + objective.dimension(),
                optimiser.x.begin());
    }
    nlopt_set_maxeval(optimiser.opt.get(), remaining);
    double final_cost = 0.0;
    code = nlopt_optimize(optimiser.opt.get(), optimiser.x.data(), &final_cost);
    if (code != NLOPT_FAILURE) break;
  }
  result.iterations = objective.evaluations();

  // L-BFGS may stop on a worse trial point; the best point it evaluated is what we keep.
  const bool have_best = StageObjective::is_usable_cost(objective.best_cost());
  const double* best = have_best ? objective.best_x().data() : guess.data();
  switch (code) {
    case NLOPT_SUCCESS:
    case NLOPT_STOPVAL_REACHED:
    case NLOPT_FTOL_REACHED:
    case NLOPT_XTOL_REACHED:
      result.status = PlanStatus::Ok;
      result.reason = "converged";
      break;
    case NLOPT_ROUNDOFF_LIMITED:
      // Luksan's L-BFGS reports this when the line search cannot improve in floating
      // point: at the optimum for all practical purposes.
      result.status = PlanStatus::Ok;
      result.reason = "converged to rounding precision";
      break;
    case NLOPT_MAXEVAL_REACHED:
    case NLOPT_MAXTIME_REACHED:
      result.status = PlanStatus::EarlyStop;
      result.reason = code == NLOPT_MAXEVAL_REACHED ? "stopped at max_evaluations"
                                                    : "stopped at max_solve_time_s";
      break;
    default:
      result.status = have_best && objective.best_cost() < guess_cost ? PlanStatus::EarlyStop
                                                                      : PlanStatus::Failed;
      // Typically NLOPT_FAILURE: the line search gave up on a badly scaled (long) stage.
      result.reason = std::string("L-BFGS gave up (NLopt ") + nlopt_result_to_string(code) +
                      "); keeping the best point it evaluated";
      break;
  }

  if (result.status != PlanStatus::Failed) {
    result.trajectory = objective.trajectory(best);
    if (result.trajectory.is_finite()) return result;
    result.status = PlanStatus::Failed;
    result.reason = "optimised trajectory was not finite";
  }
  result.reason += "; flying the safe initial guess";
  result.trajectory = objective.trajectory(guess.data());
  if (!result.trajectory.is_finite()) {
    result.reason = "initial guess was not finite; holding the start";
    result.trajectory = Trajectory::hold(start);
  }
  return result;
}

}  // namespace cover::planner
