#include "cover/sampc/intercept_velocity.hpp"

#include <algorithm>
#include <cmath>

namespace cover::sampc {

InterceptParams InterceptParams::load(config::YamlReader reader) {
  InterceptParams p;
  reader.optional("min_ugv_speed_m_s", p.min_ugv_speed_m_s);
  reader.optional("max_ugv_yaw_rate_rad_s", p.max_ugv_yaw_rate_rad_s);
  reader.optional("max_time_to_go_s", p.max_time_to_go_s);
  reader.optional("max_predicted_turn_rad", p.max_predicted_turn_rad);
  reader.optional("velocity_nodes", p.velocity_nodes);
  reader.reject_unknown_keys();
  return p;
}

void InterceptParams::validate(const std::string& context) const {
  config::check(std::isfinite(min_ugv_speed_m_s) && min_ugv_speed_m_s >= 0.0,
                context + ".min_ugv_speed_m_s", "must be finite and >= 0");
  config::check(std::isfinite(max_ugv_yaw_rate_rad_s) && max_ugv_yaw_rate_rad_s > 0.0,
                context + ".max_ugv_yaw_rate_rad_s", "must be finite and > 0");
  config::check(
      std::isfinite(max_time_to_go_s) && max_time_to_go_s > 0.0 && max_time_to_go_s <= 60.0,
      context + ".max_time_to_go_s", "must be in (0, 60]");
  // Up to a full circle, where the mean velocity is zero.
  config::check(std::isfinite(max_predicted_turn_rad) && max_predicted_turn_rad > 0.0 &&
                    max_predicted_turn_rad <= 6.3,
                context + ".max_predicted_turn_rad", "must be in (0, 6.3]");
}

const char* to_string(InterceptFallback fallback) {
  switch (fallback) {
    case InterceptFallback::None:
      return "none";
    case InterceptFallback::NoSpeed:
      return "no-speed";
    case InterceptFallback::Reversing:
      return "reversing";
    case InterceptFallback::SlowUgv:
      return "slow-ugv";
    case InterceptFallback::FastTurn:
      return "fast-turn";
    case InterceptFallback::BadInput:
      return "bad-input";
  }
  return "unknown";
}

Eigen::Vector2d ugv_mean_velocity(double speed_m_s, double yaw_rate_rad_s, double tau_s) {
  const double turn = yaw_rate_rad_s * tau_s;
  // sin(x) / x and (1 - cos(x)) / x; their series below 1e-4 (error < 1e-17).
  if (std::abs(turn) < 1e-4) {
    return speed_m_s * Eigen::Vector2d(1.0 - turn * turn / 6.0, 0.5 * turn);
  }
  return speed_m_s * Eigen::Vector2d(std::sin(turn) / turn, (1.0 - std::cos(turn)) / turn);
}

InterceptFallback prediction_fallback(const InterceptParams& params, const model::UgvMotion& ugv) {
  if (!ugv.speed_valid()) return InterceptFallback::NoSpeed;
  if (ugv.speed_m_s < 0.0) return InterceptFallback::Reversing;
  if (ugv.speed_m_s < params.min_ugv_speed_m_s) return InterceptFallback::SlowUgv;
  const double w = ugv.angular_velocity_rad_s.z();
  if (!(std::abs(w) <= params.max_ugv_yaw_rate_rad_s) || !ugv.angular_velocity_rad_s.allFinite()) {
    return InterceptFallback::FastTurn;
  }
  return InterceptFallback::None;
}

namespace {

InterceptFallback why_not(const InterceptParams& params, const model::UgvMotion& ugv,
                          const Eigen::Vector3d& p_m, double speed_xy_m_s,
                          const Eigen::Vector2d& eq30_m_s, double speed_limit_m_s) {
  if (!p_m.allFinite() || !eq30_m_s.allFinite() || !std::isfinite(speed_xy_m_s) ||
      !(speed_limit_m_s >= 0.0)) {
    return InterceptFallback::BadInput;
  }
  return prediction_fallback(params, ugv);
}

}  // namespace

InterceptVelocity intercept_velocity(const InterceptParams& params, const model::UgvMotion& ugv,
                                     const Eigen::Vector3d& p_m, double speed_xy_m_s,
                                     const Eigen::Vector2d& eq30_m_s, double speed_limit_m_s) {
  InterceptVelocity out;
  out.velocity_m_s = eq30_m_s;
  out.fallback = why_not(params, ugv, p_m, speed_xy_m_s, eq30_m_s, speed_limit_m_s);
  if (out.fallback != InterceptFallback::None) return out;

  const double u = ugv.speed_m_s;
  const double w = ugv.angular_velocity_rad_s.z();
  // tau = |p_xy| / s, capped; s = 0 (a reference at rest) gives the cap.
  double tau = params.max_time_to_go_s;
  const double distance = p_m.head<2>().norm();
  if (speed_xy_m_s > 0.0) tau = std::min(tau, distance / speed_xy_m_s);
  if (std::abs(w) > 0.0) tau = std::min(tau, params.max_predicted_turn_rad / std::abs(w));
  out.time_to_go_s = tau;

  const Eigen::Vector2d lead = ugv_mean_velocity(u, w, tau) - Eigen::Vector2d(u, 0.0);
  // The velocity relative to the UGV's translation, v + Omega x p, within the limit; eq. 30's
  // own speed s is never cut.
  const Eigen::Vector2d rotation = ugv.angular_velocity_rad_s.cross(p_m).head<2>();
  Eigen::Vector2d relative = eq30_m_s + rotation + lead;
  const double limit = std::max(speed_limit_m_s, std::abs(speed_xy_m_s));
  const double speed = relative.norm();
  if (speed > limit) relative *= limit / speed;
  out.velocity_m_s = relative - rotation;
  return out;
}

}  // namespace cover::sampc
