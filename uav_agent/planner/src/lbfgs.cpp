#include "cover/planner/lbfgs.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace cover::planner {

namespace {

using Clock = std::chrono::steady_clock;

// Weak Wolfe conditions: sufficient decrease (Armijo) and curvature.
constexpr double kSufficientDecrease = 1e-4;
constexpr double kCurvature = 0.9;
// Trials of one line search: 40 halvings take a step below 1e-12 of the first.
constexpr int kMaxLineSearchTrials = 40;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

bool relatively_close(double a, double b, double tolerance) {
  return std::abs(a - b) < tolerance * 0.5 * (std::abs(a) + std::abs(b));
}

}  // namespace

void Lbfgs::resize(int dimension, int memory) {
  x_.setZero(dimension);
  g_.setZero(dimension);
  d_.setZero(dimension);
  x_trial_.setZero(dimension);
  g_trial_.setZero(dimension);
  x_lo_.setZero(dimension);
  g_lo_.setZero(dimension);
  alpha_.setZero(memory);
  rho_.setZero(memory);
  s_.setZero(dimension, memory);
  y_.setZero(dimension, memory);
}

// d = -H g by the two-loop recursion over the `stored` newest pairs, H0 = (s'y / y'y) I.
void Lbfgs::search_direction(int stored, int newest) {
  const int memory = static_cast<int>(s_.cols());
  d_ = -g_;
  int i = newest;
  for (int j = 0; j < stored; ++j) {
    alpha_(i) = rho_(i) * s_.col(i).dot(d_);
    d_ -= alpha_(i) * y_.col(i);
    i = (i + memory - 1) % memory;
  }
  d_ /= rho_(newest) * y_.col(newest).squaredNorm();
  i = (newest + memory - stored + 1) % memory;
  for (int j = 0; j < stored; ++j) {
    const double beta = rho_(i) * y_.col(i).dot(d_);
    d_ += (alpha_(i) - beta) * s_.col(i);
    i = (i + 1) % memory;
  }
}

LbfgsResult Lbfgs::minimize(LbfgsObjective objective, void* data, const LbfgsSettings& settings,
                            double* x, double& cost, int& evaluations) {
  const auto started = Clock::now();
  const int memory = static_cast<int>(s_.cols());
  Eigen::Map<Eigen::VectorXd> x_out(x, dimension());
  const auto out_of_budget = [&](LbfgsResult& why) {
    if (evaluations >= settings.max_evaluations) {
      why = LbfgsResult::MaxEvaluations;
      return true;
    }
    if (settings.max_solve_time_s > 0.0 &&
        std::chrono::duration<double>(Clock::now() - started).count() > settings.max_solve_time_s) {
      why = LbfgsResult::MaxTime;
      return true;
    }
    return false;
  };

  x_ = x_out;
  evaluations = 1;
  double f = objective(x_.data(), g_.data(), data);
  cost = f;
  if (!std::isfinite(f) || !g_.allFinite()) return LbfgsResult::LineSearchFailed;
  int stored = 0;
  int newest = memory - 1;
  LbfgsResult result = LbfgsResult::MaxEvaluations;
  for (;;) {
    if (!(g_.squaredNorm() > 0.0)) {
      result = LbfgsResult::CostConverged;  // a stationary point
      break;
    }
    if (stored > 0) search_direction(stored, newest);
    double slope = stored > 0 ? g_.dot(d_) : 0.0;
    if (!(slope < 0.0)) {  // no memory yet, or it lost descent: steepest descent, forget it
      stored = 0;
      d_ = -g_;
      slope = -g_.squaredNorm();
    }
    // A unit-length first step (the caller scales the problem); then the quasi-Newton step.
    double step = stored > 0 ? 1.0 : 1.0 / d_.norm();
    double lo = 0.0, hi = std::numeric_limits<double>::infinity();
    double f_lo = f;
    bool accepted = false;
    bool budget_hit = false;
    for (int trial = 0; trial < kMaxLineSearchTrials; ++trial) {
      if (out_of_budget(result)) {
        budget_hit = true;
        break;
      }
      x_trial_ = x_ + step * d_;
      ++evaluations;
      const double f_trial = objective(x_trial_.data(), g_trial_.data(), data);
      if (!(f_trial <= f + kSufficientDecrease * step * slope) || !g_trial_.allFinite()) {
        hi = step;
      } else if (g_trial_.dot(d_) < kCurvature * slope) {
        lo = step;  // acceptable decrease, still steeply downhill: keep it, look further
        f_lo = f_trial;
        x_lo_.swap(x_trial_);
        g_lo_.swap(g_trial_);
      } else {
        accepted = true;
        f_lo = f_trial;
        x_lo_.swap(x_trial_);
        g_lo_.swap(g_trial_);
        break;
      }
      step = std::isinf(hi) ? 2.0 * step : 0.5 * (lo + hi);
      // The step no longer moves x in floating point: nothing left to find on this line.
      if (step * d_.cwiseAbs().maxCoeff() <= kEpsilon * x_.cwiseAbs().maxCoeff()) break;
    }
    if (!accepted && lo == 0.0) {
      if (!budget_hit) result = LbfgsResult::RoundoffLimited;
      break;
    }
    // Accepted, or the last point with sufficient decrease (curvature unmet within the
    // trials): move there and go on.
    const bool step_small =
        ((x_lo_ - x_).array().abs() <
         settings.relative_step_tolerance * 0.5 * (x_lo_.array().abs() + x_.array().abs()))
            .all();
    const bool cost_small = relatively_close(f, f_lo, settings.relative_cost_tolerance);
    const double sy = (x_lo_ - x_).dot(g_lo_ - g_);
    const double yy = (g_lo_ - g_).squaredNorm();
    if (sy > kEpsilon * yy) {  // positive curvature: keep the pair (H stays positive definite)
      newest = (newest + 1) % memory;
      s_.col(newest) = x_lo_ - x_;
      y_.col(newest) = g_lo_ - g_;
      rho_(newest) = 1.0 / sy;
      stored = std::min(stored + 1, memory);
    }
    x_.swap(x_lo_);
    g_.swap(g_lo_);
    f = f_lo;
    cost = f;
    if (cost_small) {
      result = LbfgsResult::CostConverged;
      break;
    }
    if (step_small) {
      result = LbfgsResult::StepConverged;
      break;
    }
    if (budget_hit) break;
  }
  x_out = x_;
  return result;
}

}  // namespace cover::planner
