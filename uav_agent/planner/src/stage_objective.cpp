#include "cover/planner/stage_objective.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cover::planner {

namespace {
// d^Order/ds^Order of one quintic piece at s, by Horner's rule. Written out because
// Eigen's generic row-vector products are not inlined and would dominate the cost function.
template <int Order>
Eigen::RowVector3d evaluate_derivative(const Eigen::Matrix<double, 6, 3>& coefficients, double s) {
  Eigen::RowVector3d value = Eigen::RowVector3d::Zero();
  for (int k = 5; k >= Order; --k) {
    double falling_factorial = 1.0;
    for (int m = 0; m < Order; ++m) falling_factorial *= (k - m);
    for (int axis = 0; axis < 3; ++axis) {
      value[axis] = value[axis] * s + falling_factorial * coefficients(k, axis);
    }
  }
  return value;
}
}  // namespace

StageObjective::StageObjective(const PlannerParams& params)
    : params_(params), pieces_(params.pieces) {
  minco_.set_conditions(Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), pieces_);
  taus_.setZero(pieces_);
  durations_.setOnes(pieces_);
  waypoints_.setZero(3, pieces_ - 1);
  gradient_by_coefficients_.setZero(6 * pieces_, 3);
  partial_gradient_by_durations_.setZero(pieces_);
  gradient_by_durations_.setZero(pieces_);
  gradient_by_waypoints_.setZero(3, pieces_ - 1);
  absolute_time_sensitivity_.setZero(pieces_);
  best_x_.setZero(dimension());
  reset_tracking();
}

void StageObjective::set_problem(const Eigen::Vector3d& start_position_m,
                                 const Eigen::Vector3d& initial_velocity_m_s,
                                 const Eigen::Vector3d& initial_acceleration_m_s2,
                                 const Eigen::Vector3d& goal_position_m, double vmax_m_s,
                                 double amax_m_s2) {
  Eigen::Matrix3d head = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d tail = Eigen::Matrix3d::Zero();
  head.col(0) = start_position_m;
  head.col(1) = initial_velocity_m_s;
  head.col(2) = initial_acceleration_m_s2;
  tail.col(0) = goal_position_m;
  minco_.set_conditions(head, tail, pieces_);
  vmax_m_s_ = vmax_m_s;
  amax_m_s2_ = amax_m_s2;
  initial_speed_m_s_ = initial_velocity_m_s.norm();
  overspeed_decel_m_s2_ = params_.overspeed_decel_fraction * amax_m_s2;
  cost_scale_ = 1.0;
  reset_tracking();
}

void StageObjective::reset_tracking() {
  evaluations_ = 0;
  best_cost_ = std::numeric_limits<double>::infinity();
}

double StageObjective::duration_from_tau(double tau) {
  if (tau > 0.0) return (0.5 * tau + 1.0) * tau + 1.0;
  return 1.0 / ((0.5 * tau - 1.0) * tau + 1.0);
}

double StageObjective::tau_from_duration(double duration_s) {
  if (duration_s > 1.0) return std::sqrt(2.0 * duration_s - 1.0) - 1.0;
  return 1.0 - std::sqrt(2.0 / duration_s - 1.0);
}

double StageObjective::duration_derivative(double tau) {
  if (tau > 0.0) return tau + 1.0;
  const double denominator = (0.5 * tau - 1.0) * tau + 1.0;
  return (1.0 - tau) / (denominator * denominator);
}

void StageObjective::encode(const Eigen::Matrix3Xd& waypoints, const Eigen::VectorXd& durations,
                            double* x) const {
  for (int i = 0; i < pieces_; ++i) {
    const double above_floor = durations(i) - params_.min_piece_duration_s;
    x[i] = tau_from_duration(std::max(above_floor, 1e-3));
  }
  for (int i = 0; i < pieces_ - 1; ++i) {
    for (int axis = 0; axis < 3; ++axis) x[pieces_ + 3 * i + axis] = waypoints(axis, i);
  }
}

void StageObjective::decode(const double* x) {
  for (int i = 0; i < pieces_; ++i) {
    taus_(i) = x[i];
    durations_(i) = params_.min_piece_duration_s + duration_from_tau(x[i]);
  }
  for (int i = 0; i < pieces_ - 1; ++i) {
    for (int axis = 0; axis < 3; ++axis) waypoints_(axis, i) = x[pieces_ + 3 * i + axis];
  }
}

// Speed limit at absolute time t: vm, except when the stage starts faster than vm (e.g. a
// frame switch); then it decays from |v0| at a fraction of am until it reaches vm.
double StageObjective::speed_limit_at(double t_s) const {
  if (initial_speed_m_s_ <= vmax_m_s_) return vmax_m_s_;
  return std::max(vmax_m_s_, initial_speed_m_s_ - overspeed_decel_m_s2_ * t_s);
}

// Eqs. 17-22 with trapezoid weights; the excesses are normalised by vm^2 and am^2.
double StageObjective::add_penalties() {
  const int kappa = params_.samples_per_piece;
  const double inverse_vm2 = 1.0 / (vmax_m_s_ * vmax_m_s_);
  const double inverse_am2 = 1.0 / (amax_m_s2_ * amax_m_s2_);
  const auto& c = minco_.coefficients();
  double penalty = 0.0;
  double piece_start_s = 0.0;
  absolute_time_sensitivity_.setZero();
  for (int i = 0; i < pieces_; ++i) {
    const double duration = durations_(i);
    const double step = duration / kappa;
    // Fixed-size local copies: the strided blocks of the 6M x 3 matrices are much slower.
    const Eigen::Matrix<double, 6, 3> coefficients = c.middleRows<6>(6 * i);
    Eigen::Matrix<double, 6, 3> gradient = Eigen::Matrix<double, 6, 3>::Zero();
    for (int j = 0; j <= kappa; ++j) {
      const double fraction = static_cast<double>(j) / kappa;
      const double s1 = fraction * duration, s2 = s1 * s1, s3 = s2 * s1, s4 = s3 * s1;
      const double trapezoid = (j == 0 || j == kappa) ? 0.5 : 1.0;
      Eigen::Matrix<double, 6, 1> beta1, beta2;
      beta1 << 0.0, 1.0, 2.0 * s1, 3.0 * s2, 4.0 * s3, 5.0 * s4;
      beta2 << 0.0, 0.0, 2.0, 6.0 * s1, 12.0 * s2, 20.0 * s3;
      const Eigen::RowVector3d velocity = evaluate_derivative<1>(coefficients, s1);
      const Eigen::RowVector3d acceleration = evaluate_derivative<2>(coefficients, s1);

      const double limit = speed_limit_at(piece_start_s + s1);
      const double speed_excess = (velocity.squaredNorm() - limit * limit) * inverse_vm2;
      if (speed_excess > 0.0) {
        const double weight = params_.speed_penalty_weight * trapezoid * step;
        const double excess2 = speed_excess * speed_excess;
        penalty += weight * excess2 * speed_excess;
        const double d_excess = 3.0 * weight * excess2;  // d penalty / d excess
        gradient.noalias() += (2.0 * inverse_vm2 * d_excess) * beta1 * velocity;
        partial_gradient_by_durations_(i) +=
            params_.speed_penalty_weight * trapezoid / kappa * excess2 * speed_excess +
            d_excess * 2.0 * inverse_vm2 * fraction * velocity.dot(acceleration);
        if (limit > vmax_m_s_) {  // limit decays with absolute time while above vm
          const double d_excess_d_time = 2.0 * limit * overspeed_decel_m_s2_ * inverse_vm2;
          absolute_time_sensitivity_(i) += d_excess * d_excess_d_time;
          partial_gradient_by_durations_(i) += d_excess * d_excess_d_time * fraction;
        }
      }

      const double acc_excess =
          (acceleration.squaredNorm() - amax_m_s2_ * amax_m_s2_) * inverse_am2;
      if (acc_excess > 0.0) {
        const Eigen::RowVector3d jerk = evaluate_derivative<3>(coefficients, s1);
        const double weight = params_.acc_penalty_weight * trapezoid * step;
        const double excess2 = acc_excess * acc_excess;
        penalty += weight * excess2 * acc_excess;
        const double d_excess = 3.0 * weight * excess2;
        gradient.noalias() += (2.0 * inverse_am2 * d_excess) * beta2 * acceleration;
        partial_gradient_by_durations_(i) +=
            params_.acc_penalty_weight * trapezoid / kappa * excess2 * acc_excess +
            d_excess * 2.0 * inverse_am2 * fraction * acceleration.dot(jerk);
      }
    }
    gradient_by_coefficients_.middleRows<6>(6 * i) += gradient;
    piece_start_s += duration;
  }
  // A sample of piece i moves with every earlier duration: suffix sums keep this O(M).
  double later_sensitivity = 0.0;
  for (int i = pieces_ - 1; i >= 0; --i) {
    partial_gradient_by_durations_(i) += later_sensitivity;
    later_sensitivity += absolute_time_sensitivity_(i);
  }
  return penalty;
}

double StageObjective::evaluate(const double* x, double* gradient) {
  ++evaluations_;
  decode(x);
  minco_.set_parameters(waypoints_, durations_);

  gradient_by_coefficients_.setZero();
  partial_gradient_by_durations_.setConstant(params_.time_weight);
  double cost = minco_.jerk_energy() + params_.time_weight * durations_.sum();
  minco_.add_jerk_energy_gradient(gradient_by_coefficients_, partial_gradient_by_durations_);
  cost += add_penalties();
  cost *= cost_scale_;

  if (!std::isfinite(cost) || !minco_.coefficients().allFinite()) {
    if (gradient != nullptr) {
      for (int k = 0; k < dimension(); ++k) gradient[k] = 0.0;
    }
    return kUnusableCost;
  }
  if (cost < best_cost_) {
    best_cost_ = cost;
    for (int k = 0; k < dimension(); ++k) best_x_(k) = x[k];
  }
  if (gradient == nullptr) return cost;

  minco_.propagate_gradient(gradient_by_coefficients_, partial_gradient_by_durations_,
                            gradient_by_waypoints_, gradient_by_durations_);
  for (int i = 0; i < pieces_; ++i) {
    gradient[i] = cost_scale_ * gradient_by_durations_(i) * duration_derivative(taus_(i));
  }
  for (int i = 0; i < pieces_ - 1; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      gradient[pieces_ + 3 * i + axis] = cost_scale_ * gradient_by_waypoints_(axis, i);
    }
  }
  return cost;
}

Trajectory StageObjective::trajectory(const double* x) {
  decode(x);
  minco_.set_parameters(waypoints_, durations_);
  return minco_.trajectory();
}

void StageObjective::write_trajectory(const double* x, Trajectory& out) {
  decode(x);
  minco_.set_parameters(waypoints_, durations_);
  minco_.write_trajectory(out);
}

}  // namespace cover::planner
