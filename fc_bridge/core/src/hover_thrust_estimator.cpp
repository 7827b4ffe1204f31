#include "cover/fc_bridge/hover_thrust_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace cover::fc_bridge {
namespace {
// A prediction step longer than this (a pause in the measurements) grows the doubt no more.
constexpr double kMaxPredict_s = 1.0;
// Specific forces beyond this are not a flying quadrotor (a crash, a broken sample).
constexpr double kMaxSpecificForce_g = 4.0;
}  // namespace

HoverThrustEstimator::HoverThrustEstimator(const HoverThrustEstimatorParams& params)
    : params_(params),
      hover_(std::clamp(params.initial, params.min, params.max)),
      variance_(params.initial_std * params.initial_std) {}

double HoverThrustEstimator::standard_deviation() const {
  return std::sqrt(variance_);
}

bool HoverThrustEstimator::restart_from(double initial) {
  if (!std::isfinite(initial) || initial <= 0.0 || initial >= 1.0) return false;
  hover_ = std::clamp(initial, params_.min, params_.max);
  variance_ = params_.initial_std * params_.initial_std;
  last_update_s_ = -1.0;
  return true;
}

bool HoverThrustEstimator::update(double thrust, double specific_force_up_m_s2, double now_s) {
  const double g = params_.gravity_m_s2;
  if (!std::isfinite(thrust) || !std::isfinite(specific_force_up_m_s2) || !std::isfinite(now_s) ||
      thrust <= 0.0 || thrust > 1.0 || std::abs(specific_force_up_m_s2) > kMaxSpecificForce_g * g) {
    return false;
  }
  // Predict: the truth wanders slowly.
  if (last_update_s_ >= 0.0) {
    const double dt = std::clamp(now_s - last_update_s_, 0.0, kMaxPredict_s);
    const double q = params_.noise_per_sqrt_s;
    variance_ = std::min(variance_ + q * q * dt, params_.initial_std * params_.initial_std);
  }
  last_update_s_ = now_s;
  // Update with f = g u / h: H = df/dh = -g u / h^2.
  const double predicted = g * thrust / hover_;
  const double h_jacobian = -g * thrust / (hover_ * hover_);
  const double r = params_.accel_noise_m_s2 * params_.accel_noise_m_s2;
  const double innovation_variance = h_jacobian * h_jacobian * variance_ + r;
  const double gain = variance_ * h_jacobian / innovation_variance;
  const double next = hover_ + gain * (specific_force_up_m_s2 - predicted);
  if (!std::isfinite(next)) return false;
  hover_ = std::clamp(next, params_.min, params_.max);
  variance_ = std::max((1.0 - gain * h_jacobian) * variance_, 1e-10);
  return true;
}

}  // namespace cover::fc_bridge
