#include "cover/fc_bridge/hover_thrust_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace cover::fc_bridge {
namespace {
// A prediction step longer than this (a pause in the measurements) grows the doubt no more.
constexpr double kMaxPredict_s = 1.0;
// Specific forces beyond this are not a flying quadrotor (a crash, a broken sample).
constexpr double kMaxSpecificForce_g = 4.0;
// Vertical speeds beyond this are not a hover-thrust measurement (a broken sample).
constexpr double kMaxVelocity_m_s = 50.0;
// Below this cos(tilt) the vehicle is on its side: not a hover.
constexpr double kMinTiltCos = 0.5;
constexpr double kMinVariance = 1e-12;

bool usable_thrust(double thrust) {
  return std::isfinite(thrust) && thrust > 0.0 && thrust <= 1.0;
}
}  // namespace

HoverThrustEstimator::HoverThrustEstimator(const HoverThrustEstimatorParams& params)
    : params_(params),
      hover_(std::clamp(params.initial, params.min, params.max)),
      p_hh_(params.initial_std * params.initial_std) {}

double HoverThrustEstimator::standard_deviation() const {
  return std::sqrt(p_hh_);
}

bool HoverThrustEstimator::restart_from(double initial) {
  if (!std::isfinite(initial) || initial <= 0.0 || initial >= 1.0) return false;
  hover_ = std::clamp(initial, params_.min, params_.max);
  p_hh_ = params_.initial_std * params_.initial_std;
  p_hv_ = p_vv_ = 0.0;
  velocity_known_ = false;
  last_velocity_s_ = -1.0;
  last_update_s_ = -1.0;
  return true;
}

void HoverThrustEstimator::set_tilt_cos(double tilt_cos) {
  if (std::isfinite(tilt_cos)) tilt_cos_ = std::clamp(tilt_cos, kMinTiltCos, 1.0);
}

void HoverThrustEstimator::drop_stale_velocity(double now_s) {
  if (velocity_known_ && now_s - last_velocity_s_ > params_.velocity_timeout_s) {
    velocity_known_ = false;
    p_hv_ = p_vv_ = 0.0;
  }
}

// From the last measurement to `now_s` under `thrust`: the truth wanders, and the velocity
// follows v' = g u c / h - g - d v, whose Jacobian is -g u c / h^2 in h and -d in v.
void HoverThrustEstimator::predict(double thrust, double now_s) {
  drop_stale_velocity(now_s);
  if (last_update_s_ < 0.0) return;
  const double dt = std::clamp(now_s - last_update_s_, 0.0, kMaxPredict_s);
  const double q = params_.noise_per_sqrt_s;
  const double max_p_hh = params_.initial_std * params_.initial_std;
  if (!velocity_known_) {
    p_hh_ = std::min(p_hh_ + q * q * dt, max_p_hh);
    return;
  }
  const double g = params_.gravity_m_s2;
  const double drive = g * thrust * tilt_cos_;
  const double decay = std::max(0.0, 1.0 - params_.velocity_drag_per_s * dt);  // d v_next / d v
  velocity_ = velocity_ * decay + (drive / hover_ - g) * dt;
  const double f = -drive * dt / (hover_ * hover_);  // d v_next / d h
  const double qv = params_.velocity_model_noise_m_s_per_sqrt_s;
  // P' = F P F^T + Q with F = [[1, 0], [f, decay]].
  const double p_hh = p_hh_;
  const double p_hv = decay * p_hv_ + f * p_hh;
  const double p_vv = decay * decay * p_vv_ + 2.0 * f * decay * p_hv_ + f * f * p_hh + qv * qv * dt;
  p_hh_ = std::min(p_hh + q * q * dt, max_p_hh);
  p_hv_ = p_hv;
  p_vv_ = p_vv;
}

bool HoverThrustEstimator::update(double thrust, double specific_force_up_m_s2, double now_s) {
  const double g = params_.gravity_m_s2;
  if (!usable_thrust(thrust) || !std::isfinite(specific_force_up_m_s2) || !std::isfinite(now_s) ||
      std::abs(specific_force_up_m_s2) > kMaxSpecificForce_g * g) {
    return false;
  }
  predict(thrust, now_s);
  last_update_s_ = now_s;
  // Update with f = g u / h: H = [df/dh, 0] = [-g u / h^2, 0].
  const double predicted = g * thrust / hover_;
  const double h = -g * thrust / (hover_ * hover_);
  const double r = params_.accel_noise_m_s2 * params_.accel_noise_m_s2;
  const double s = h * h * p_hh_ + r;
  const double k_h = p_hh_ * h / s;
  const double k_v = p_hv_ * h / s;
  const double innovation = specific_force_up_m_s2 - predicted;
  const double next = hover_ + k_h * innovation;
  if (!std::isfinite(next)) return false;
  hover_ = std::clamp(next, params_.min, params_.max);
  // P' = (I - K H) P, H = [h, 0].
  const double p_hh = p_hh_, p_hv = p_hv_;
  p_hh_ = std::max(p_hh - k_h * h * p_hh, kMinVariance);
  if (velocity_known_) {
    velocity_ += k_v * innovation;
    p_hv_ = p_hv - k_h * h * p_hv;
    p_vv_ = std::max(p_vv_ - k_v * h * p_hv, kMinVariance);
  }
  return true;
}

bool HoverThrustEstimator::update_velocity(double thrust, double velocity_up_m_s, double now_s) {
  if (!usable_thrust(thrust) || !std::isfinite(velocity_up_m_s) || !std::isfinite(now_s) ||
      std::abs(velocity_up_m_s) > kMaxVelocity_m_s) {
    return false;
  }
  predict(thrust, now_s);
  last_update_s_ = now_s;
  last_velocity_s_ = now_s;
  const double r = params_.velocity_noise_m_s * params_.velocity_noise_m_s;
  if (!velocity_known_) {  // the first sample (again): the velocity state starts at it
    velocity_known_ = true;
    velocity_ = velocity_up_m_s;
    p_vv_ = r;
    p_hv_ = 0.0;
    return true;
  }
  // H = [0, 1].
  const double s = p_vv_ + r;
  const double k_h = p_hv_ / s;
  const double k_v = p_vv_ / s;
  const double innovation = velocity_up_m_s - velocity_;
  const double next = hover_ + k_h * innovation;
  if (!std::isfinite(next)) return false;
  hover_ = std::clamp(next, params_.min, params_.max);
  velocity_ += k_v * innovation;
  const double p_hh = p_hh_, p_hv = p_hv_, p_vv = p_vv_;
  p_hh_ = std::max(p_hh - k_h * p_hv, kMinVariance);
  p_hv_ = p_hv - k_h * p_vv;
  p_vv_ = std::max(p_vv - k_v * p_vv, kMinVariance);
  return true;
}

}  // namespace cover::fc_bridge
