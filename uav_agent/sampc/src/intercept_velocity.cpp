#include "cover/sampc/intercept_velocity.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace cover::sampc {

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

namespace {

// D(tau) / tau at speed u + a t and yaw rate w: the mean over tau of [cos, sin](w t) (the
// speed's term) and of t [cos, sin](w t) / tau (the acceleration's); their series below
// |w tau| = 1e-2 (errors below 1e-12 relative).
Eigen::Vector2d mean_velocity_at_constant_acceleration(double u, double w, double a, double tau) {
  const double turn = w * tau;
  Eigen::Vector2d heading_mean, ramp_mean;
  if (std::abs(turn) < 1e-2) {
    const double t2 = turn * turn;
    heading_mean = Eigen::Vector2d(1.0 - t2 / 6.0, 0.5 * turn * (1.0 - t2 / 12.0));
    ramp_mean = Eigen::Vector2d(0.5 - t2 / 8.0 + t2 * t2 / 144.0, turn / 3.0 - turn * t2 / 30.0);
  } else {
    const double s = std::sin(turn), c = std::cos(turn);
    heading_mean = Eigen::Vector2d(s / turn, (1.0 - c) / turn);
    ramp_mean = Eigen::Vector2d(s / turn + (c - 1.0) / (turn * turn), s / (turn * turn) - c / turn);
  }
  return u * heading_mean + a * tau * ramp_mean;
}

}  // namespace

Eigen::Vector2d ugv_mean_velocity(double speed_m_s, double yaw_rate_rad_s, double tau_s,
                                  double forward_acceleration_m_s2) {
  const double u = speed_m_s, a = forward_acceleration_m_s2;
  // A braking UGV stops rather than reverses: from its stop on it stays where it is.
  if (u >= 0.0 && a < 0.0 && u + a * tau_s < 0.0) {
    const double stop_s = u / -a;
    return mean_velocity_at_constant_acceleration(u, yaw_rate_rad_s, a, stop_s) * (stop_s / tau_s);
  }
  return mean_velocity_at_constant_acceleration(u, yaw_rate_rad_s, a, tau_s);
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

double predicted_forward_acceleration_m_s2(const InterceptParams& params,
                                           const model::UgvMotion& ugv) {
  const double a = ugv.forward_acceleration_m_s2;
  if (!params.use_ugv_acceleration || !std::isfinite(a)) return 0.0;
  return std::clamp(a, -params.max_ugv_acceleration_m_s2, params.max_ugv_acceleration_m_s2);
}

namespace {

// The velocity relative to the UGV's translation now that flies from p to D(tau) in tau.
Eigen::Vector2d straight_relative_velocity(double u, double w, double a, const Eigen::Vector2d& p,
                                           double tau) {
  return ugv_mean_velocity(u, w, tau, a) - p / tau - Eigen::Vector2d(u, 0.0);
}

bool all_finite(std::initializer_list<double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// Narrows [infeasible, feasible] (values f_infeasible > 0 >= f_feasible) to `tolerance`
// and returns its feasible end. Illinois steps (regula falsi, the end kept twice in a row
// has its value halved) take ~6 evaluations where bisection takes 20-30 for the same
// tolerance; a pair of steps that does not halve the bracket is followed by a bisection, so
// the bracket at least halves every three evaluations whatever the function's shape. This
// runs for every intercept node every control period: the evaluations are its cost.
template <typename Infeasibility>
double narrow_to_feasible(double infeasible, double f_infeasible, double feasible,
                          double f_feasible, double tolerance, const Infeasibility& infeasibility) {
  int kept_side = 0;  // +1: the infeasible end moved last, -1: the feasible end
  double width_two_steps_ago = feasible - infeasible;
  double width_one_step_ago = width_two_steps_ago;
  while (feasible - infeasible > tolerance) {
    const double width = feasible - infeasible;
    double t = infeasible + width * f_infeasible / (f_infeasible - f_feasible);
    const bool stalled = width > 0.5 * width_two_steps_ago;
    if (!(t > infeasible && t < feasible) || stalled || !(f_infeasible > 0.0)) {
      t = 0.5 * (infeasible + feasible);
      width_two_steps_ago = width;  // a bisection restarts the halving count
    } else {
      width_two_steps_ago = width_one_step_ago;
    }
    width_one_step_ago = width;
    const double f = infeasibility(t);
    if (f > 0.0) {
      infeasible = t;
      f_infeasible = f;
      if (kept_side == +1) f_feasible *= 0.5;
      kept_side = +1;
    } else {
      feasible = t;
      f_feasible = f;
      if (kept_side == -1) f_infeasible *= 0.5;
      kept_side = -1;
    }
  }
  return feasible;
}

// The first time in (lo, hi] at which `infeasibility` is <= 0: a 24-point grid for the first
// feasible cell, then that cell narrowed to 2^-halvings of its width; nullopt when no grid
// point is feasible. `lo` itself is taken as infeasible (the callers start where the
// excess is >= 0). `surely_infeasible(t)`, a cheap bound, answers for a grid point it is
// sure of, so the full evaluation runs only where the bound cannot tell: the same cell,
// the same answer. The infeasible end's value is computed when the narrowing needs it.
template <typename Infeasibility, typename Bound>
std::optional<double> first_feasible_time_s(double lo, double hi, int halvings,
                                            const Infeasibility& infeasibility,
                                            const Bound& surely_infeasible) {
  constexpr int kGrid = 24;
  const double step = (hi - lo) / kGrid;
  const double tolerance = std::ldexp(step, -halvings);
  double infeasible = lo;
  std::optional<double> f_infeasible;
  for (int i = 1; i <= kGrid; ++i) {
    const double t = lo + step * i;
    if (surely_infeasible(t)) {
      infeasible = t;
      f_infeasible.reset();
      continue;
    }
    const double f = infeasibility(t);
    if (f > 0.0) {
      infeasible = t;
      f_infeasible = f;
      continue;
    }
    if (!f_infeasible) f_infeasible = infeasibility(infeasible);
    return narrow_to_feasible(infeasible, *f_infeasible, t, f, tolerance, infeasibility);
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> earliest_time_to_go_s(double speed_m_s, double yaw_rate_rad_s,
                                            const Eigen::Vector2d& p_m, double approach_speed_m_s,
                                            double tau_max_s, double forward_acceleration_m_s2) {
  if (!all_finite({speed_m_s, yaw_rate_rad_s, p_m.x(), p_m.y(), approach_speed_m_s, tau_max_s,
                   forward_acceleration_m_s2})) {
    return std::nullopt;
  }
  const double distance = p_m.norm();
  if (!(distance > 0.0)) return 0.0;
  const double u = std::abs(speed_m_s), s = std::max(approach_speed_m_s, 0.0);
  // |vbar - u| <= 2u + |a| tau_max, so no arrival before distance / (s + 2u + |a| tau_max) is
  // slow enough: the search starts there, where the excess speed is >= 0.
  const double tau_lo =
      distance / (s + 2.0 * u + std::abs(forward_acceleration_m_s2) * std::max(tau_max_s, 0.0));
  if (!(tau_lo < tau_max_s)) return std::nullopt;
  // The limit holds relative to the UGV's translation now, as eq. 30's: the law is
  // re-solved every step. (Holding it against the UGV's velocity over the whole flight, as it
  // turns, leaves no straight flight on most long transitions: Table 1 at (0.8, 0.35) 1.119.)
  const auto excess = [&](double tau) {
    return straight_relative_velocity(speed_m_s, yaw_rate_rad_s, forward_acceleration_m_s2, p_m,
                                      tau)
               .norm() -
           s;
  };
  // The excess need not be monotone: a turning UGV first comes closer, then recedes.
  return first_feasible_time_s(tau_lo, tau_max_s, 30, excess, [](double) { return false; });
}

namespace {

// The UGV's predicted forward speed t_s from now: u + a t, a forward-driving UGV stopped at
// zero rather than reversing.
double predicted_speed_m_s(double speed_m_s, double forward_acceleration_m_s2, double t_s) {
  const double speed = speed_m_s + forward_acceleration_m_s2 * t_s;
  return speed_m_s >= 0.0 ? std::max(speed, 0.0) : speed;
}

}  // namespace

namespace {

// fastest_speed_along on components: inlined into the Simpson loop below, which the compiler
// then vectorises (17 square roots per call).
inline double fastest_speed_along(double dx, double dy, double vx, double vy, double limit_m_s) {
  // |lambda d - v| = s: lambda = d.v + sqrt(s^2 - |v|^2 + (d.v)^2), the far root.
  const double along = dx * vx + dy * vy;
  const double discriminant = limit_m_s * limit_m_s - (vx * vx + vy * vy) + along * along;
  if (!(discriminant >= 0.0)) return 0.0;
  return std::max(along + std::sqrt(discriminant), 0.0);
}

}  // namespace

Eigen::Vector2d ugv_velocity_at(double speed_m_s, double yaw_rate_rad_s, double t_s,
                                double forward_acceleration_m_s2) {
  const double speed = predicted_speed_m_s(speed_m_s, forward_acceleration_m_s2, t_s);
  const double heading = yaw_rate_rad_s * t_s;
  return speed * Eigen::Vector2d(std::cos(heading), std::sin(heading));
}

double fastest_speed_along(const Eigen::Vector2d& direction, const Eigen::Vector2d& velocity_m_s,
                           double limit_m_s) {
  return fastest_speed_along(direction.x(), direction.y(), velocity_m_s.x(), velocity_m_s.y(),
                             limit_m_s);
}

namespace {

// Intervals of the Simpson rule for the fastest straight flight's distance.
constexpr int kSimpsonIntervals = 16;

// How far a flight along `direction` gets in tau at the fastest speed the limit allows at
// every instant against the UGV's predicted velocity: Simpson's rule on 16 intervals (the
// integrand is smooth: the velocity turns by at most max_predicted_turn_rad over tau). The
// UGV's heading advances by one rotation per node (one sin/cos per call, not one per node:
// this runs ~50 times per node and step).
double fastest_straight_distance_m(double u, double w, double a, const Eigen::Vector2d& direction,
                                   double limit, double tau) {
  constexpr int kIntervals = kSimpsonIntervals;
  constexpr int kPoints = kIntervals + 1;
  const double h = tau / kIntervals;
  const Eigen::Rotation2Dd step(w * h);
  // The UGV's predicted velocity at each point first (the heading is a recurrence), then
  // the square roots in one loop the compiler vectorises, then the sum in Simpson's order.
  std::array<double, kPoints> vx, vy, fastest;
  Eigen::Vector2d heading = Eigen::Vector2d::UnitX();
  for (int i = 0; i < kPoints; ++i) {
    const Eigen::Vector2d velocity = predicted_speed_m_s(u, a, i * h) * heading;
    vx[i] = velocity.x();
    vy[i] = velocity.y();
    heading = step * heading;
  }
  for (int i = 0; i < kPoints; ++i) {
    fastest[i] = fastest_speed_along(direction.x(), direction.y(), vx[i], vy[i], limit);
  }
  double sum = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * fastest[i];
  }
  return sum * h / 3.0;
}

// How far short of `to_target` (the UGV's predicted position after tau, from the UAV) the
// fastest straight flight of `tau` toward it falls (<= 0: it gets there); its direction.
double fastest_straight_shortfall_m(double u, double w, double a, const Eigen::Vector2d& p,
                                    const Eigen::Vector2d& to_target, double limit, double tau,
                                    Eigen::Vector2d& direction) {
  const double length = to_target.norm();
  if (!(length > 0.0)) {
    direction = -p.normalized();
    return 0.0;
  }
  direction = to_target / length;
  return length - fastest_straight_distance_m(u, w, a, direction, limit, tau);
}

}  // namespace

std::optional<StraightFlight> earliest_fastest_straight_flight(
    double speed_m_s, double yaw_rate_rad_s, const Eigen::Vector2d& p_m, double approach_speed_m_s,
    double tau_max_s, double forward_acceleration_m_s2) {
  if (!all_finite({speed_m_s, yaw_rate_rad_s, p_m.x(), p_m.y(), approach_speed_m_s, tau_max_s,
                   forward_acceleration_m_s2})) {
    return std::nullopt;
  }
  const double distance = p_m.norm();
  if (!(distance > 0.0)) return StraightFlight{};
  const double u = speed_m_s, w = yaw_rate_rad_s, a = forward_acceleration_m_s2;
  const double s = std::max(approach_speed_m_s, 0.0);
  // No flight is faster than s + the UGV's fastest speed within tau_max: no arrival before.
  const double fastest = s + std::abs(u) + std::abs(a) * std::max(tau_max_s, 0.0);
  const double tau_lo = distance / (2.0 * fastest);
  if (!(tau_lo < tau_max_s)) return std::nullopt;
  // Where the UGV will be after tau, from the UAV: both the bound and the shortfall need it
  // at the same tau (one sin/cos pair each), so the last one is kept.
  double offset_tau = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d offset;
  const auto to_target = [&](double tau) -> const Eigen::Vector2d& {
    if (!(tau == offset_tau)) {
      offset = ugv_mean_velocity(u, w, tau, a) * tau - p_m;
      offset_tau = tau;
    }
    return offset;
  };
  // The search's answer is its last feasible evaluation: its direction is kept.
  Eigen::Vector2d feasible_direction = -p_m / distance;
  const auto shortfall = [&](double tau) {
    Eigen::Vector2d direction;
    const double f = fastest_straight_shortfall_m(u, w, a, p_m, to_target(tau), s, tau, direction);
    if (f <= 0.0) feasible_direction = direction;
    return f;
  };
  // Simpson's weights are positive and sum to tau, and the fastest speed along d against
  // the UGV's velocity v is at most d.v + s: no flight of tau covers more than d.D(tau) +
  // s tau, up to Simpson's error on d.v (bounded below from its fourth derivative; where a
  // braking UGV stops within tau the kink leaves only the cruder bound tau (s + the UGV's
  // fastest speed)). A target farther than that is surely not reached, without the
  // integral: the same grid cell, the same answer.
  const auto stops_within = [&](double tau) { return u >= 0.0 && a < 0.0 && u + a * tau < 0.0; };
  const auto surely_short = [&](double tau) {
    // The UGV's speed u + a t stops at 0 driving forward (predicted_speed_m_s).
    const double fastest_ugv =
        u >= 0.0 ? std::max(u, u + a * tau) : std::abs(u) + std::abs(a) * tau;
    const double reach = tau * (s + fastest_ugv) * (1.0 + 1e-9);
    const Eigen::Vector2d& offset = to_target(tau);
    const double length = offset.norm();
    if (length > reach) return true;
    if (stops_within(tau) || !(length > 0.0)) return false;
    const double h = tau / kSimpsonIntervals, w4 = w * w * w * w;
    const double simpson_error =
        tau / 180.0 * h * h * h * h * (fastest_ugv * w4 + 4.0 * std::abs(a * w * w * w));
    const Eigen::Vector2d ugv_travel = offset + p_m;
    const double along = offset.dot(ugv_travel) / length;
    return length > (along + s * tau) * (1.0 + 1e-9) + 2.0 * simpson_error + 1e-9;
  };
  // The grid's cell (<= 0.25 s) narrowed 2^20 times: to 2.4e-7 s.
  const std::optional<double> tau =
      first_feasible_time_s(tau_lo, tau_max_s, 20, shortfall, surely_short);
  if (!tau) return std::nullopt;
  return StraightFlight{*tau, feasible_direction};
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
  const double a = predicted_forward_acceleration_m_s2(params, ugv);
  // The prediction's horizon: capped in time and in the UGV's turn.
  double tau_max = params.max_time_to_go_s;
  if (std::abs(w) > 0.0) tau_max = std::min(tau_max, params.max_predicted_turn_rad / std::abs(w));
  const Eigen::Vector2d p = p_m.head<2>();
  const double distance = p.norm();
  // The velocity relative to the UGV's translation, v + Omega x p; eq. 30's is -p_hat s.
  const Eigen::Vector2d rotation = ugv.angular_velocity_rad_s.cross(p_m).head<2>();
  Eigen::Vector2d relative = eq30_m_s + rotation;
  double tau = tau_max;
  // The solve only while the approach runs at the speed limit: on the braking curve near the
  // UGV (s below it) the solved aim arrived with a sideways velocity and the short final
  // stage tracked worse (Scenario 1: 1.9 / 1.6 cm against 1.1 / 1.0 in x / y); there the lead
  // goes on top of eq. 30 as below, and vanishes with tau.
  const bool solves = params.solve_time_to_go && speed_xy_m_s > 0.0 &&
                      speed_xy_m_s >= speed_limit_m_s * (1.0 - 1e-9);
  // The fastest flight leans on the UGV's whole predicted velocity profile: only while its
  // yaw rate holds (on an S-curve the constant-velocity aim, which needs only the mean, flew
  // shorter).
  const bool steady_turn = std::abs(ugv.angular_acceleration_rad_s2.z()) <=
                           params.fastest_flight_max_yaw_acceleration_rad_s2;
  if (solves && params.fastest_straight_flight && steady_turn) {
    if (const auto flight = earliest_fastest_straight_flight(u, w, p, speed_xy_m_s, tau_max, a)) {
      out.time_to_go_s = flight->time_to_go_s;
      if (flight->time_to_go_s > 0.0) {
        const Eigen::Vector2d ugv_now(u, 0.0);
        relative =
            fastest_speed_along(flight->direction, ugv_now, speed_xy_m_s) * flight->direction -
            ugv_now;
      }
      out.velocity_m_s = relative - rotation;
      return out;
    }
  }
  const std::optional<double> earliest =
      solves ? earliest_time_to_go_s(u, w, p, speed_xy_m_s, tau_max, a) : std::nullopt;
  if (earliest) {
    tau = *earliest;
    // On the axis (tau = 0) there is nothing to lead: eq. 30.
    if (tau > 0.0) relative = straight_relative_velocity(u, w, a, p, tau);
  } else {
    // No straight flight within the prediction's horizon (or no solve): tau = |p_xy| / s,
    // capped (s = 0, a reference at rest, gives the cap), the lead on top of eq. 30.
    if (speed_xy_m_s > 0.0) tau = std::min(tau, distance / speed_xy_m_s);
    relative += ugv_mean_velocity(u, w, tau, a) - Eigen::Vector2d(u, 0.0);
  }
  out.time_to_go_s = tau;
  // Within the limit; eq. 30's own speed s is never cut.
  const double limit = std::max(speed_limit_m_s, std::abs(speed_xy_m_s));
  const double speed = relative.norm();
  if (speed > limit) relative *= limit / speed;
  out.velocity_m_s = relative - rotation;
  return out;
}

}  // namespace cover::sampc
