#pragma once

#include <Eigen/Core>
#include <vector>

#include "cover/sim/ugv_motion_pattern.hpp"
#include "cover/vocabulary/motion_limits.hpp"

namespace cover::sim {

// A lower bound on the world-frame path length L_t of a transition stage: the shortest
// horizontal path from the stage's start (position, velocity) that keeps the task's limits
// and arrives where the stage would end, at any time within a budget. Table 1 prints its
// L_t/L_s as `bound_ratio` next to the eq. 30 law's (approach_law.hpp): no method flying
// the same start within these limits can be shorter, so the bound tells what is physically
// out of reach from what a better controller or law could still gain.
//
// The limits, as the methods fly them:
//   speed    |v - v_target| <= vmax: the task's vmax relative to the target UGV's
//            translation (eq. 30's approach; the planner's eq. 15 relative limit). A start
//            already faster than that (the velocity of the UGV it left) may slow down at
//            the relative acceleration bound below, no faster.
//   accel    |a| <= amax + |a_target|max: the ball holding both readings of the limit, the
//            world |a| <= amax (eq. 30's clip) and the relative |a - a_target| <= amax
//            (eq. 15's), so the bound holds for either.
//   arrival  |p(T) - p_target(T)| <= reach tolerance and |v(T) - v_target(T)| <= speed
//            threshold + |yaw rate|max * reach tolerance: the stage machine's own test
//            (MissionParams::transition_reach_tolerance_m, speed_threshold_m_s), which it
//            applies in the target's rotating frame, whose velocity differs from the
//            world's relative velocity by at most yaw rate * distance.
//
// How it is computed. For a fixed arrival time T the problem is convex. The path is taken
// at the grid t_k = k T / N (step near time_step_s) as a polyline p_0..p_N; u_k = (p_(k+1) -
// p_k) / dt is the mean velocity over segment k. Any continuous flight within the limits
// gives a polyline meeting, exactly: |u_k - mean target velocity| <= the speed limit at
// the segment's start; |u_k - u_(k-1)| <= A dt and |u_0 - v_0| <= A dt / 2 (A the
// acceleration bound: a difference of means of v over windows dt apart); |p_N - p_target|
// <= tolerance; |u_(N-1) - v_target(T)| <= speed threshold + A dt / 2. Its length is at most
// the flight's (chords are no longer than arcs). So the shortest such polyline, a
// second-order cone program (cone_program.hpp: own sparse barrier method, because the
// problem is banded, ~100-300 variables, solved some 30 times per transition; a dense SQP
// such as NLopt's SLSQP costs O(n^3) per iteration and needs a smooth objective, and the
// barrier's duality gap certifies the value as a lower bound), bounds every flight
// arriving at T from below, for any dt.
//
// T is then searched over (0, budget]: a coarse grid, refined around its best point by
// golden-section steps. Between the evaluated T the minimum is not certified (the length
// varies continuously with T; arrival_resolution_s sets how finely it is resolved). The
// budget is the transition's own flown duration: the method's own flight then is one of
// the candidates, so its L_t cannot beat the bound, and "no path arriving by then is
// shorter" compares like with like. A longer budget would let the bound wait for the target
// to come round, which a method that flies the stage as soon as it starts never does.
struct TransitionBoundParams {
  double vmax_m_s = mission::kDefaultVmax_m_s;    // speed limit relative to the target UGV
  double amax_m_s2 = mission::kDefaultAmax_m_s2;  // acceleration limit
  double reach_tolerance_m = 0.3;                 // MissionParams::transition_reach_tolerance_m
  double speed_threshold_m_s = 0.3;               // MissionParams::speed_threshold_m_s
  double time_step_s = 0.1;                       // polyline segment (nominal)
  double coarse_arrival_step_s = 0.5;             // arrival-time grid before the refinement
  double arrival_resolution_s = 0.05;             // refinement stops at this bracket width
  double gap_tolerance_m = 1e-4;                  // duality gap of each convex solve
};

struct TransitionBoundResult {
  bool reached = false;                 // some arrival within the budget is feasible
  double arrival_time_s = 0.0;          // T*, from the start
  double path_length_m = 0.0;           // the bound on L_t (certified for T*)
  double straight_length_m = 0.0;       // L_s of the bound's path: |p(T*) - p_0|
  std::vector<Eigen::Vector2d> path_m;  // the shortest polyline, world, p_0 .. p_N
  int solves = 0;                       // convex problems solved (arrival times tried)
};

// From `start_position_m` / `start_velocity_m_s` (world, horizontal) at `start_time_s`
// toward the UGV driving `target`, arriving within `budget_s`.
TransitionBoundResult shortest_transition_bound(const UgvMotionPattern& target, double start_time_s,
                                                const Eigen::Vector2d& start_position_m,
                                                const Eigen::Vector2d& start_velocity_m_s,
                                                double budget_s,
                                                const TransitionBoundParams& params);

}  // namespace cover::sim
