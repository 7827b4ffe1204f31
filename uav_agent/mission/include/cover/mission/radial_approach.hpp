#pragma once

#include <Eigen/Core>

#include "cover/sampc/horizon_reference.hpp"
#include "cover/vocabulary/motion_limits.hpp"

namespace cover::mission {

// The transition stage's horizontal reference as a straight approach to the target UGV's
// axis, seen from where the UAV is now. At the transition stage SAMPC tracks only the
// squared horizontal distance of the reference (xy-z-ref) and eq. 30's approach speed v0d.
// Taking both from the stage's MINCO plan ties the approach to a path planned once, at the
// frame switch, as if the frame did not turn: its radius shrinks at the plan's radial
// speed, well below its speed when the start velocity points off the UGV, and the heavy
// distance term holds the UAV to it (a Scenario 2 start closed at 0.95 m/s with vmax 1.5).
// This reference closes the distance as eq. 30 intends, at the approach speed
// min(vmax, sqrt(2 a_brake r)), reached from the current closing speed at most amax faster
// per second, and is re-derived every control step from the measured distance.
struct RadialApproachLimits {
  double vmax_m_s = kDefaultVmax_m_s;    // the process's speed limit relative to the UGV
  double amax_m_s2 = kDefaultAmax_m_s2;  // the process's acceleration limit, for speeding up
  double brake_m_s2 = 1.0;               // the deceleration the approach plans to stop with
  // The speed-up's acceleration builds from 0 to amax over this long after the stage starts
  // (s; 0: amax at once). A step to amax at the frame switch is a step in the tilt the
  // heavy distance term asks for: the body-rate and thrust steps of Fig. 8.
  double speed_up_ramp_s = 0.0;
};

// The speed of the braking curve at radius `radius_m`: min(vmax, sqrt(2 a_brake r)).
double braking_speed_m_s(double radius_m, const RadialApproachLimits& limits);

// How much faster than now the approach may close `elapsed_s` from now, `stage_time_s`
// into the stage: the integral of the speed-up's ramped acceleration.
double speed_up_m_s(double stage_time_s, double elapsed_s, const RadialApproachLimits& limits);

// The approach speed at radius `radius_m`, `elapsed_s` after the closing speed was
// `closing_speed_m_s` at `stage_time_s` into the stage.
double approach_speed_m_s(double radius_m, double closing_speed_m_s, double stage_time_s,
                          double elapsed_s, const RadialApproachLimits& limits);

// Overwrites the horizontal parts of nodes 0..horizon_steps of `reference` (spaced step_s):
// positions on the line from the UAV's horizontal position `position_m` to the axis at the
// approach's predicted radius (speeding up from the closing speed now), velocities along it
// at the braking curve's speed there (node 0's is eq. 30's v0d). `closing_speed_m_s` is the UAV's
// speed toward the axis relative to the UGV's translation now (negative: moving away), at
// `stage_time_s` into the transition stage. Heights are left as they are.
void fill_radial_approach(const Eigen::Vector3d& position_m, double closing_speed_m_s,
                          double stage_time_s, const RadialApproachLimits& limits,
                          int horizon_steps, double step_s, sampc::HorizonReference& reference);

}  // namespace cover::mission
