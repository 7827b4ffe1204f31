#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::sampc {

// The `intercept` method's transition-stage velocity law (beyond the paper). Everything is
// in the target UGV's frame G (UGV at the origin, x forward, rotating at w = Omega_z), the
// UGV driving forward at u. The model's velocity v is a rate in G, so the UAV's inertial
// velocity in G's axes is v + Omega x p + [u, 0, 0].
//
// Eq. 30 asks for v + Omega x p = -p_hat s: approach at s relative to the UGV's translation,
// which makes the UAV copy the UGV's curve. Intercept aims where the UGV will be instead:
// with u and w held, after tau the UGV is at D(tau) = u [sin(w tau), 1 - cos(w tau)] / w;
// flying straight from p to D(tau) in tau is the inertial velocity vbar(tau) - p / tau, with
// vbar = D / tau the UGV's mean velocity over the time to go. The time to go is the
// earliest arrival the speed allows (solve_time_to_go): the smallest tau at which that
// straight flight's velocity relative to the UGV's translation, (D(tau) - p) / tau - [u, 0],
// is no faster than the approach speed s (eq. 30's v0d, the braking curve's). Taking
// tau = |p_xy| / s instead (the law without the solve) adds the lead on top of the approach
// at s and then cuts the sum back to the speed limit: where the lead is large (a fast,
// turning UGV) it eats the approach and the UAV arrives later, and elsewhere, than aimed.
// The solve runs while the approach is at the speed limit; on the braking curve near the
// UGV (s below it) the lead goes on top of eq. 30 (tau = |p_xy| / s), which matches the
// UGV's velocity more gently before the final stage.
//     v_ref = eq. 30 + vbar(tau) - [u, 0, 0] + (p_hat s - p / tau)   (the "lead")
// As tau -> 0 the lead vanishes: the end of the stage (match the UGV) is eq. 30's.
struct InterceptParams {
  // Below this forward speed (m/s) the UGV's future position is not worth predicting (and an
  // IMU estimate, lateral force over yaw rate, is at its noisiest): eq. 30. Reversing
  // (u < 0) always falls back. Default 0.1.
  double min_ugv_speed_m_s = 0.1;
  // Above this |yaw rate| (rad/s) a constant-turn prediction over seconds is not trusted
  // (the UGV is manoeuvring, not cruising): eq. 30. Default 1.0.
  double max_ugv_yaw_rate_rad_s = 1.0;
  // The time to go tau = |p_xy| / s is capped at this (s): a far target (or a slow
  // reference) does not extrapolate a circle for a minute. Default 6.0.
  double max_time_to_go_s = 6.0;
  // ... and so that the UGV turns at most this much over tau (rad): near a full circle the
  // mean velocity shrinks to nothing and the prediction means little. Default 2.5.
  double max_predicted_turn_rad = 2.5;
  // The law sits on the first `velocity_nodes` free nodes (cover's custom_velocity_nodes,
  // for this method), each at its own predicted position: a lead on node 1 alone is mostly
  // undone by the rest of the horizon; 10 nodes under the reachable-change limit (SampcParams::
  // eq30_acceleration_limit_m_s2) fly the shortest paths with every switch peak below
  // coni-mpc's. In [1, horizon_steps]. Default 10 (docs/benchmarks.md).
  int velocity_nodes = 10;
  // Solve for the earliest arrival time (a 1-D search per node: a grid from the earliest
  // possible arrival, then bisection), rather than tau = |p_xy| / s. Default true
  // (docs/benchmarks.md: Table 1 at (0.8, 0.35) 1.096 -> 1.082 on 100 runs).
  bool solve_time_to_go = true;
  // Predict with the UGV's along-track acceleration too (UgvMotion::forward_acceleration_m_s2,
  // its own accelerometer), the speed u + a t held over tau and cut at zero (a braking UGV
  // stops). Without it a straight-driving UGV's prediction is its velocity now, and the
  // law is exactly eq. 30's collision course: it copies every speed change of the target.
  bool use_ugv_acceleration = true;
  // With solve_time_to_go: the straight flight to the predicted UGV goes at the fastest speed
  // the limit allows at every instant against the UGV's predicted velocity (which turns),
  // rather than at one constant velocity checked against the UGV's velocity now. Re-solved
  // each step, a constant-velocity aim is no longer allowed once the UGV has turned, and the
  // world path bends with each new aim; the fastest flight's tail is the next step's answer.
  bool fastest_straight_flight = true;
  // ... while the UGV's |yaw acceleration| is at most this (rad/s^2): the flight leans on the
  // whole predicted velocity profile, which a changing turn (an S-curve) makes wrong within a
  // second. Beyond it, the constant-velocity aim. Default 0.1.
  double fastest_flight_max_yaw_acceleration_rad_s2 = 0.1;
  // |a| is clamped to this (m/s^2): a bump or a hard brake is not extrapolated for seconds.
  // In [0, 10]. Default 1.0.
  double max_ugv_acceleration_m_s2 = 1.0;

  // Each field once (config/param_fields.hpp): SampcParams loads, checks, tests and
  // documents this list as its sub-section `intercept`. velocity_nodes' upper bound is the
  // horizon, checked by SampcParams::validate.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("min_ugv_speed_m_s", self.min_ugv_speed_m_s,
          Field("m/s", "below this forward speed (or reversing): eq. 30").at_least(0.0));
    visit("max_ugv_yaw_rate_rad_s", self.max_ugv_yaw_rate_rad_s,
          Field("rad/s", "above this |yaw rate|: eq. 30").above(0.0));
    visit("max_time_to_go_s", self.max_time_to_go_s,
          Field("s", "the time to go is capped at this").above(0.0).at_most(60.0));
    // Up to a full circle, where the mean velocity is zero.
    visit("max_predicted_turn_rad", self.max_predicted_turn_rad,
          Field("rad", "... and so that the UGV turns at most this much over it")
              .above(0.0)
              .at_most(6.3));
    visit("velocity_nodes", self.velocity_nodes,
          Field("", "free nodes 1..n carrying the law; <= horizon_steps").at_least(1.0));
    visit("solve_time_to_go", self.solve_time_to_go,
          Field("", "solve for the earliest arrival rather than |p_xy| / s"));
    visit("use_ugv_acceleration", self.use_ugv_acceleration,
          Field("", "predict with the UGV's along-track acceleration too"));
    visit("max_ugv_acceleration_m_s2", self.max_ugv_acceleration_m_s2,
          Field("m/s^2", "|a| of the prediction clamped to this").at_least(0.0).at_most(10.0));
    visit("fastest_straight_flight", self.fastest_straight_flight,
          Field("", "aim at the fastest straight flight against the predicted velocity"));
    visit("fastest_flight_max_yaw_acceleration_rad_s2",
          self.fastest_flight_max_yaw_acceleration_rad_s2,
          Field("rad/s^2", "... while the UGV's |yaw acceleration| is at most this").at_least(0.0));
  }
};

// Why the law fell back to eq. 30 (none: it did not).
enum class InterceptFallback : std::uint8_t {
  None = 0,
  NoSpeed = 1,    // the UGV's speed estimate is not valid (unknown source or not finite)
  Reversing = 2,  // u < 0
  SlowUgv = 3,    // 0 <= u < min_ugv_speed_m_s
  FastTurn = 4,   // |w| > max_ugv_yaw_rate_rad_s (or not finite)
  BadInput = 5,   // a non-finite position, eq. 30 velocity, reference speed or limit
};

const char* to_string(InterceptFallback fallback);

struct InterceptVelocity {
  Eigen::Vector2d velocity_m_s = Eigen::Vector2d::Zero();  // the rate in G to track
  InterceptFallback fallback = InterceptFallback::None;
  double time_to_go_s = 0.0;  // tau used (0 when it fell back)
};

// The UGV's mean velocity over the next tau seconds at forward speed u + a t and yaw rate w,
// in G's axes now: D(tau) / tau (tau = 0: [u, 0]). A forward-driving UGV that brakes to a
// stop within tau stays there (it is not predicted to reverse). Finite for finite inputs.
Eigen::Vector2d ugv_mean_velocity(double speed_m_s, double yaw_rate_rad_s, double tau_s,
                                  double forward_acceleration_m_s2 = 0.0);

// The along-track acceleration the prediction uses: the UGV's, clamped to
// max_ugv_acceleration_m_s2; 0 when not used or not finite.
double predicted_forward_acceleration_m_s2(const InterceptParams& params,
                                           const model::UgvMotion& ugv);

// Whether the UGV's motion allows the prediction at all (speed estimate, direction, yaw
// rate): None, or why not. intercept_velocity() also checks its other inputs.
InterceptFallback prediction_fallback(const InterceptParams& params, const model::UgvMotion& ugv);

// The earliest time to go tau in (0, tau_max] at which flying straight from `p_m` to the
// UGV's predicted position needs a velocity relative to its translation now of at most
// `approach_speed_m_s`; nullopt when none does (the UGV outruns the approach within the
// prediction's horizon: the law then takes tau = |p_xy| / s). 0 at the axis; nullopt for
// a non-finite input.
std::optional<double> earliest_time_to_go_s(double speed_m_s, double yaw_rate_rad_s,
                                            const Eigen::Vector2d& p_m, double approach_speed_m_s,
                                            double tau_max_s,
                                            double forward_acceleration_m_s2 = 0.0);

// The UGV's predicted velocity t_s from now, in G's axes now (speed u + a t; a forward-driving
// UGV stops at zero, as ugv_mean_velocity).
Eigen::Vector2d ugv_velocity_at(double speed_m_s, double yaw_rate_rad_s, double t_s,
                                double forward_acceleration_m_s2 = 0.0);

// The fastest speed along the unit `direction` whose velocity is within `limit_m_s` of
// `velocity_m_s` (the far end of the ray's chord through that disc); 0 when the ray misses it.
double fastest_speed_along(const Eigen::Vector2d& direction, const Eigen::Vector2d& velocity_m_s,
                           double limit_m_s);

struct StraightFlight {
  double time_to_go_s = 0.0;
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, toward the meeting point
};

// The earliest meeting with the UGV on a straight line flown at the fastest speed within
// `approach_speed_m_s` of the UGV's predicted velocity at every instant (tau in (0,
// tau_max]); nullopt when none within the horizon, or for a non-finite input; time 0 at the
// axis.
std::optional<StraightFlight> earliest_fastest_straight_flight(
    double speed_m_s, double yaw_rate_rad_s, const Eigen::Vector2d& p_m, double approach_speed_m_s,
    double tau_max_s, double forward_acceleration_m_s2 = 0.0);

// The intercept velocity reference at position `p_m` (in G), from eq. 30's value there
// (`eq30_m_s`, computed by the caller for the same p, Omega and s) and the reference
// speed s (`speed_xy_m_s`). The UAV's velocity relative to the UGV's translation,
// v + Omega x p, is kept within max(speed_limit_m_s, s). Returns eq. 30 bit for bit, with
// the reason, whenever the prediction is not trusted; never a NaN from finite eq30_m_s.
InterceptVelocity intercept_velocity(const InterceptParams& params, const model::UgvMotion& ugv,
                                     const Eigen::Vector3d& p_m, double speed_xy_m_s,
                                     const Eigen::Vector2d& eq30_m_s, double speed_limit_m_s);

}  // namespace cover::sampc
