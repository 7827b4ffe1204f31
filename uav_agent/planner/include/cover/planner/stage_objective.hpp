#pragma once

#include <Eigen/Core>
#include <cmath>

#include "cover/planner/minco.hpp"
#include "cover/planner/planner_params.hpp"
#include "cover/planner/trajectory.hpp"

namespace cover::planner {

// The unconstrained cost the stage planner hands to L-BFGS (paper eqs. 14-22):
//   sum_i integral ||jerk||^2 + rho T_i + speed and acceleration time-integral penalties,
// as a function of x = [tau_1..tau_M, q_1, .., q_{M-1}], where T_i = T(tau_i) > 0 is the
// smooth positive time map of GCOPTER and q the free intermediate waypoints. The gradient is
// exact (MINCO adjoint). Buffers are sized at construction; evaluate() does not allocate.
class StageObjective {
 public:
  // What evaluate() returns at a point where MINCO broke down (durations so short the
  // system is singular): large but finite, so that the L-BFGS line search simply backs off.
  static constexpr double kUnusableCost = 1.0e30;
  // False for kUnusableCost and for what is not finite: no point worth keeping has it.
  static bool is_usable_cost(double cost) { return std::isfinite(cost) && cost < kUnusableCost; }

  explicit StageObjective(const PlannerParams& params);

  // Boundary conditions: start (p0, v0, a0), end (goal, 0, 0); limits vm, am.
  void set_problem(const Eigen::Vector3d& start_position_m,
                   const Eigen::Vector3d& initial_velocity_m_s,
                   const Eigen::Vector3d& initial_acceleration_m_s2,
                   const Eigen::Vector3d& goal_position_m, double vmax_m_s, double amax_m_s2);

  int dimension() const { return 4 * pieces_ - 3; }
  int pieces() const { return pieces_; }
  void encode(const Eigen::Matrix3Xd& waypoints, const Eigen::VectorXd& durations, double* x) const;

  // Multiplies cost and gradient. The planner scales the cost to a unit gradient at the
  // initial guess, so that the tolerances are relative to the guess and L-BFGS's first
  // (unit-length) step is well sized; the minimiser is unchanged.
  void set_cost_scale(double scale) { cost_scale_ = scale; }
  double cost_scale() const { return cost_scale_; }

  // Cost at x (times the cost scale); writes the gradient when `gradient` is not null. Tracks the
  // best x seen.
  double evaluate(const double* x, double* gradient);
  // The trajectory at x (allocates: for tests and tools).
  Trajectory trajectory(const double* x);
  // The trajectory at x into `out`, reusing its storage.
  void write_trajectory(const double* x, Trajectory& out);

  int evaluations() const { return evaluations_; }
  double best_cost() const { return best_cost_; }
  const Eigen::VectorXd& best_x() const { return best_x_; }
  void reset_tracking();

  // Positive, C1, monotone time map: T = (tau/2 + 1) tau + 1 for tau > 0, else
  // 1 / ((tau/2 - 1) tau + 1); quadratic growth keeps long stages well scaled. The
  // objective adds params.min_piece_duration_s to it (see duration_of).
  static double duration_from_tau(double tau);
  static double tau_from_duration(double duration_s);
  static double duration_derivative(double tau);

 private:
  void decode(const double* x);
  double add_penalties();
  double speed_limit_at(double t_s) const;

  PlannerParams params_;
  int pieces_;
  MinimumJerkMinco minco_;
  double vmax_m_s_ = 1.0;
  double amax_m_s2_ = 2.0;
  double initial_speed_m_s_ = 0.0;
  double overspeed_decel_m_s2_ = 1.0;

  Eigen::VectorXd taus_;
  Eigen::VectorXd durations_;
  Eigen::Matrix3Xd waypoints_;
  MinimumJerkMinco::Coefficients gradient_by_coefficients_;
  Eigen::VectorXd partial_gradient_by_durations_;
  Eigen::VectorXd gradient_by_durations_;
  Eigen::Matrix3Xd gradient_by_waypoints_;
  // Per piece: sum of d(penalty)/d(absolute sample time); the over-speed limit depends on
  // absolute time, so every earlier duration shifts these samples.
  Eigen::VectorXd absolute_time_sensitivity_;

  double cost_scale_ = 1.0;
  int evaluations_ = 0;
  double best_cost_ = 0.0;
  Eigen::VectorXd best_x_;
};

}  // namespace cover::planner
