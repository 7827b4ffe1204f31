#include "cover/mission/radial_approach.hpp"

#include <algorithm>
#include <cmath>

namespace cover::mission {

double braking_speed_m_s(double radius_m, const RadialApproachLimits& limits) {
  return std::min(limits.vmax_m_s, std::sqrt(2.0 * limits.brake_m_s2 * std::max(radius_m, 0.0)));
}

double speed_up_m_s(double stage_time_s, double elapsed_s, const RadialApproachLimits& limits) {
  const double ramp = limits.speed_up_ramp_s;
  // The integral from 0 to t of amax * min(1, s / ramp).
  const auto ramped = [&](double t) {
    t = std::max(t, 0.0);
    if (!(ramp > 0.0)) return limits.amax_m_s2 * t;
    return t < ramp ? limits.amax_m_s2 * t * t / (2.0 * ramp) : limits.amax_m_s2 * (t - ramp / 2.0);
  };
  return ramped(stage_time_s + elapsed_s) - ramped(stage_time_s);
}

double approach_speed_m_s(double radius_m, double closing_speed_m_s, double stage_time_s,
                          double elapsed_s, const RadialApproachLimits& limits) {
  const double wanted = braking_speed_m_s(radius_m, limits);
  // Speeding up is limited by the (ramped) amax; slowing down to the braking curve is not
  // (the curve itself brakes at a_brake).
  const double reachable =
      std::max(closing_speed_m_s, 0.0) + speed_up_m_s(stage_time_s, elapsed_s, limits);
  return std::min(wanted, reachable);
}

void fill_radial_approach(const Eigen::Vector3d& position_m, double closing_speed_m_s,
                          double stage_time_s, const RadialApproachLimits& limits,
                          int horizon_steps, double step_s, sampc::HorizonReference& reference) {
  const Eigen::Vector2d horizontal = position_m.head<2>();
  const double radius0 = horizontal.norm();
  // On the axis the direction is undefined; any will do, the radius is zero there.
  const Eigen::Vector2d outward =
      radius0 > 1e-9 ? Eigen::Vector2d(horizontal / radius0) : Eigen::Vector2d::UnitX();
  // Sub-steps of the horizon's step: the braking curve bends within one 0.1 s step.
  constexpr int kSubsteps = 10;
  const double h = step_s / kSubsteps;
  double radius = radius0;
  double elapsed = 0.0;
  for (int k = 0; k <= horizon_steps; ++k) {
    reference.position_m[k].head<2>() = outward * radius;
    // The speed is the braking curve's, not the ramp's: it is eq. 30's (and intercept's)
    // v0d, and SAMPC limits its velocity references to a reachable change itself; a ramp
    // there would ask a UAV at rest near the UGV to stay at rest.
    reference.velocity_m_s[k].head<2>() = -outward * braking_speed_m_s(radius, limits);
    for (int i = 0; i < kSubsteps; ++i) {
      radius -= h * approach_speed_m_s(radius, closing_speed_m_s, stage_time_s, elapsed, limits);
      radius = std::max(radius, 0.0);
      elapsed += h;
    }
  }
}

}  // namespace cover::mission
