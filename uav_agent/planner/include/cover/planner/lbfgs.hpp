#pragma once

#include <Eigen/Core>

namespace cover::planner {

// Why Lbfgs::minimize returned.
enum class LbfgsResult {
  CostConverged,     // relative cost decrease below relative_cost_tolerance
  StepConverged,     // every variable moved less than relative_step_tolerance (relative)
  RoundoffLimited,   // no step along the search direction lowers the cost in floating point
  MaxEvaluations,    // the evaluation budget is spent
  MaxTime,           // the wall-clock budget is spent
  LineSearchFailed,  // the cost or gradient at the start is not finite
};

struct LbfgsSettings {
  int memory = 8;                         // curvature pairs kept
  double relative_cost_tolerance = 1e-5;  // |f_k - f_k+1| < tol * (|f_k| + |f_k+1|) / 2
  double relative_step_tolerance = 1e-5;  // |dx_i| < tol * (|x_i| + |x_i'|) / 2 for all i
  int max_evaluations = 400;              // cost + gradient evaluations
  double max_solve_time_s = 0.0;          // <= 0: no wall-clock budget
};

// Cost at x; writes the gradient (always requested). Must not throw.
using LbfgsObjective = double (*)(const double* x, double* gradient, void* data);

// Limited-memory BFGS (two-loop recursion, Nocedal & Wright alg. 7.4) with the Lewis-Overton
// weak-Wolfe line search (bisection and doubling), which needs only the cost to be
// continuous and piecewise smooth, as the planner's sampled penalties are. The workspace is
// sized by resize(); minimize() does not allocate.
class Lbfgs {
 public:
  void resize(int dimension, int memory);
  int dimension() const { return static_cast<int>(x_.size()); }

  // Minimises from x (overwritten with the last accepted iterate, whose cost is `cost`).
  // `evaluations` is the number of objective calls made.
  LbfgsResult minimize(LbfgsObjective objective, void* data, const LbfgsSettings& settings,
                       double* x, double& cost, int& evaluations);

 private:
  void search_direction(int stored, int newest);

  Eigen::VectorXd x_, g_, d_, x_trial_, g_trial_, x_lo_, g_lo_, alpha_, rho_;
  Eigen::MatrixXd s_, y_;  // dimension x memory, a ring of curvature pairs
};

}  // namespace cover::planner
