#pragma once

#include <cstdint>
#include <string>

#include "cover/config/param_fields.hpp"

namespace cover::mission {

// What an aborted task does once it has held its point for `abort_hold_s`.
enum class AbortAction : std::uint8_t {
  Hover = 0,  // keep holding the point in the reference frame
  Land = 1,   // descend vertically in the reference frame and disarm on contact
};
const char* to_string(AbortAction action);

// Where the transition stage's horizontal reference (the squared distance SAMPC tracks and
// eq. 30's approach speed) comes from.
enum class TransitionReference : std::uint8_t {
  Planned = 0,         // the stage's MINCO plan, as the paper does
  RadialApproach = 1,  // a straight approach re-derived each step (radial_approach.hpp)
};
const char* to_string(TransitionReference reference);

// Stage-machine and mission-controller parameters (config/mission.yaml). The paper gives
// no numbers for the stage-end test; docs/model.md suggests 0.15 m / 0.3 m/s.
struct MissionParams {
  // A stage ends when the UAV is within this distance of the stage transition point ...
  double reach_tolerance_m = 0.15;
  // ... and its speed in the reference frame is below this.
  double speed_threshold_m_s = 0.3;
  // The transition stage's own tolerance: there SAMPC tracks the squared horizontal distance
  // (xy-z-ref), whose pull vanishes like r^3 near the point, so unmodelled drag leaves a
  // horizontal offset of a couple of decimetres. The final stage (x-y-z-ref) then converges.
  double transition_reach_tolerance_m = 0.3;
  // Final actions (land, deliver) need a tighter test: they happen on a moving deck.
  double action_tolerance_m = 0.05;
  double action_speed_threshold_m_s = 0.2;
  // A stage that has not ended after this long fails the mission (clear status, hover).
  double initial_timeout_s = 30.0;
  double transition_timeout_s = 40.0;
  double final_timeout_s = 30.0;
  // The failsafe ladder (failsafe_ladder.hpp, docs/failsafes.md). A relative state of the
  // reference UGV older than this (s) is stale: emergency hover.
  double state_timeout_s = 0.1;
  // A UGV IMU older than this (s) is stale; SAMPC keeps flying on the last one for
  // imu_hold_s more (s), then emergency hover.
  double imu_timeout_s = 0.1;
  double imu_hold_s = 0.1;
  // After this long in emergency hover (s) without the inputs back: emergency landing, and
  // the task fails (StaleInput).
  double emergency_hover_s = 1.0;
  // The emergency landing's sink rate (m/s) and the gain (1/s) that levels the attitude.
  double emergency_descent_rate_m_s = 0.3;
  double emergency_level_gain_1_s = 4.0;
  // The ladder's vertical control in the hover and the landing: an acceleration around the
  // hover thrust from the height error (gain 1/s^2), the vertical speed error (1/s) and the
  // height error's integral (1/s^3; learnt only from a measured height), which is bounded
  // (m/s^2; 0.2 g).
  double emergency_height_gain_1_s2 = 2.0;
  double emergency_speed_gain_1_s = 2.5;
  double emergency_integral_gain_1_s3 = 0.5;
  double emergency_integral_limit_m_s2 = 1.962;
  // Without any relative state the landing cannot see contact: it disarms once its sinking
  // reference is this far below the frame's origin (m; the lowest ground can be there) plus
  // land_detect_gap_m, held for land_detect_time_s.
  double emergency_blind_floor_m = 1.0;
  // A stage whose reference cannot be planned after this many attempts (one per control
  // step) fails the mission (PlanningFailed).
  int max_plan_attempts = 10;
  // Plans run off the control thread: one requested at control step k is flown from step
  // k + plan_adopt_steps (its time origin is step k); until then the reference coasts at
  // the UAV's velocity. A fixed step, not "when ready", so that a lockstep run does not
  // depend on the machine's speed (PlanClock). In [0, 100]; 0 waits for the plan in the
  // step that asks for it (the synchronous behaviour, in lockstep).
  int plan_adopt_steps = 1;
  // Offset-free tracking: SAMPC's model knows neither the true mass nor drag, so a hover
  // sags and a moving frame drags the UAV off its point. An integral of the tracking error
  // estimates that missing acceleration d and SAMPC sees it through its UGV specific-force
  // parameter (a - d in eq. 5). Gain in (m/s^2) per (m s); errors are clipped before
  // integrating (anti-windup during fast stage starts) and d is bounded.
  double integral_gain_1_s3 = 8.0;
  double integral_error_clip_m = 0.2;
  double integral_limit_m_s2 = 2.0;
  // Velocity-based disturbance observer (DisturbanceObserver): the missing acceleration
  // measured as (measured - predicted) velocity change over this window, in s (0 disables),
  // integrated with this time constant, s. Works at every stage, so the final stage starts
  // knowing its frame's drag; the integral above removes what remains.
  double observer_window_s = 0.5;
  double observer_time_constant_s = 0.5;
  // Abort (operator request): hold the point where the UAV was, in the reference frame it
  // was flying in, for this long (s), then the safe action.
  double abort_hold_s = 2.0;
  AbortAction abort_action = AbortAction::Land;
  double abort_descent_rate_m_s = 0.3;
  // A descent has touched down when its reference is this far below the UAV (something
  // holds it up) ...
  double land_detect_gap_m = 0.1;
  // ... and the UAV has not moved vertically faster than this ...
  double land_detect_speed_m_s = 0.1;
  // ... for this long (s): the motors are disarmed.
  double land_detect_time_s = 0.5;
  // The transition stage's horizontal reference, and the deceleration its radial approach
  // plans to stop with, as a fraction of the process's amax (the rest is the margin SAMPC
  // has to follow it).
  TransitionReference transition_reference = TransitionReference::RadialApproach;
  double approach_brake_fraction = 0.5;
  // The approach's speed-up acceleration builds from 0 to amax over this long after the
  // frame switch (s, in [0, 5]; 0: at once), as a planned trajectory's would
  // (RadialApproachLimits::speed_up_ramp_s).
  double approach_speed_up_ramp_s = 0.5;
  // The final stage starts while the UAV still brakes from the transition's approach: its
  // plan starts with this fraction of the acceleration SAMPC had planned over its first
  // node (0: from zero acceleration). In [0, 1].
  double final_start_acceleration_fraction = 0.3;
  // Control period (the controller runs at 100 Hz). The one definition: every other copy
  // (sampc.yaml's warm-start shift, cover-sim's tick rate, the harness's control rate) is
  // checked against it at load (check_control_period).
  double control_period_s = 0.01;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    stage_fields(self, visit);
    failsafe_fields(self, visit);
    tracking_fields(self, visit);
    abort_fields(self, visit);
    approach_fields(self, visit);
  }
  template <typename Self, typename Visit>
  static void stage_fields(Self& self, Visit& visit) {
    using config::Field;
    visit("reach_tolerance_m", self.reach_tolerance_m,
          Field("m", "a stage ends within this of its end point ...").above(0.0));
    visit("transition_reach_tolerance_m", self.transition_reach_tolerance_m,
          Field("m", "the transition stage's own reach tolerance").above(0.0));
    visit("speed_threshold_m_s", self.speed_threshold_m_s,
          Field("m/s", "... and below this speed in the reference frame").above(0.0));
    visit("action_tolerance_m", self.action_tolerance_m,
          Field("m", "reach tolerance of a final action (land, deliver)").above(0.0));
    visit("action_speed_threshold_m_s", self.action_speed_threshold_m_s,
          Field("m/s", "speed threshold of a final action").above(0.0));
    visit("initial_timeout_s", self.initial_timeout_s,
          Field("s", "an initial stage not ended by then fails the mission").above(0.0));
    visit("transition_timeout_s", self.transition_timeout_s,
          Field("s", "a transition stage not ended by then fails the mission").above(0.0));
    visit("final_timeout_s", self.final_timeout_s,
          Field("s", "a final stage not ended by then fails the mission").above(0.0));
  }
  template <typename Self, typename Visit>
  static void failsafe_fields(Self& self, Visit& visit) {
    using config::Field;
    visit("state_timeout_s", self.state_timeout_s,
          Field("s", "an older relative state is stale: emergency hover").above(0.0));
    visit("imu_timeout_s", self.imu_timeout_s, Field("s", "an older UGV IMU is stale").above(0.0));
    visit("imu_hold_s", self.imu_hold_s,
          Field("s", "flown on the last IMU this much longer, then emergency hover")
              .at_least(0.0)
              .at_most(1.0));
    visit("emergency_hover_s", self.emergency_hover_s,
          Field("s", "emergency hover this long without the inputs: emergency landing")
              .above(0.0)
              .at_most(30.0));
    visit("emergency_descent_rate_m_s", self.emergency_descent_rate_m_s,
          Field("m/s", "the emergency landing's sink rate").above(0.0).at_most(1.0));
    visit("emergency_level_gain_1_s", self.emergency_level_gain_1_s,
          Field("1/s", "the gain that levels the attitude").above(0.0).at_most(20.0));
    visit("emergency_height_gain_1_s2", self.emergency_height_gain_1_s2,
          Field("1/s^2", "vertical control: height error gain").above(0.0).at_most(20.0));
    visit("emergency_speed_gain_1_s", self.emergency_speed_gain_1_s,
          Field("1/s", "vertical control: vertical speed error gain").above(0.0).at_most(20.0));
    visit("emergency_integral_gain_1_s3", self.emergency_integral_gain_1_s3,
          Field("1/s^3", "vertical control: height error integral gain")
              .at_least(0.0)
              .at_most(10.0)
              .hint("0 disables"));
    visit("emergency_integral_limit_m_s2", self.emergency_integral_limit_m_s2,
          Field("m/s^2", "vertical control: the integral's bound").at_least(0.0).at_most(5.0));
    visit("emergency_blind_floor_m", self.emergency_blind_floor_m,
          Field("m", "blind landing: disarm this far below the frame's origin (+ gap)")
              .at_least(0.0)
              .at_most(10.0));
    visit("max_plan_attempts", self.max_plan_attempts,
          Field("", "a stage not planned after this many attempts fails the mission")
              .at_least(1.0)
              .at_most(1000.0));
    visit("plan_adopt_steps", self.plan_adopt_steps,
          Field("", "a plan asked at step k is flown from step k + this")
              .at_least(0.0)
              .at_most(100.0));
  }
  template <typename Self, typename Visit>
  static void tracking_fields(Self& self, Visit& visit) {
    using config::Field;
    visit("integral_gain_1_s3", self.integral_gain_1_s3,
          Field("1/s^3", "offset-free tracking: integral gain")
              .at_least(0.0)
              .at_most(20.0)
              .hint("0 disables"));
    visit("integral_error_clip_m", self.integral_error_clip_m,
          Field("m", "errors clipped to this before integrating").above(0.0));
    visit("integral_limit_m_s2", self.integral_limit_m_s2,
          Field("m/s^2", "the integral's bound").above(0.0).at_most(10.0));
    visit("observer_window_s", self.observer_window_s,
          Field("s", "disturbance observer's velocity-change window")
              .at_least(0.0)
              .at_most(5.0)
              .hint("0 disables"));
    visit("observer_time_constant_s", self.observer_time_constant_s,
          Field("s", "disturbance observer's time constant").at_least(0.1).at_most(20.0));
  }
  template <typename Self, typename Visit>
  static void abort_fields(Self& self, Visit& visit) {
    using config::Field;
    visit("abort_hold_s", self.abort_hold_s,
          Field("s", "an aborted task holds its point this long ...").at_least(0.0));
    visit("abort_action", self.abort_action,
          Field("", "... then does this").one_of({AbortAction::Hover, AbortAction::Land}));
    visit("abort_descent_rate_m_s", self.abort_descent_rate_m_s,
          Field("m/s", "the abort landing's sink rate").above(0.0).at_most(2.0));
    visit("land_detect_gap_m", self.land_detect_gap_m,
          Field("m", "touched down: the reference this far below the UAV ...").above(0.0));
    visit("land_detect_speed_m_s", self.land_detect_speed_m_s,
          Field("m/s", "... no vertical speed above this ...").above(0.0));
    visit("land_detect_time_s", self.land_detect_time_s,
          Field("s", "... for this long: disarm").above(0.0));
  }
  template <typename Self, typename Visit>
  static void approach_fields(Self& self, Visit& visit) {
    using config::Field;
    visit("transition_reference", self.transition_reference,
          Field("", "the transition stage's horizontal reference")
              .one_of({TransitionReference::Planned, TransitionReference::RadialApproach}));
    visit("approach_brake_fraction", self.approach_brake_fraction,
          Field("", "the radial approach brakes at this fraction of amax").above(0.0).at_most(1.0));
    visit("approach_speed_up_ramp_s", self.approach_speed_up_ramp_s,
          Field("s", "the approach's speed-up acceleration builds up over this")
              .at_least(0.0)
              .at_most(5.0));
    visit("final_start_acceleration_fraction", self.final_start_acceleration_fraction,
          Field("", "the final stage starts with this fraction of SAMPC's planned acceleration")
              .at_least(0.0)
              .at_most(1.0));
    visit("control_period_s", self.control_period_s,
          Field("s", "the control period (the one definition)").above(0.0).at_most(0.1));
  }

  static MissionParams load(config::YamlReader& reader);
  static MissionParams load_file(const std::string& path);  // reads the `mission:` section
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static MissionParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

// Where MissionParams come from, as the errors name them.
inline constexpr const char* kMissionControlPeriodKey = "mission.yaml: mission.control_period_s";

// Throws config::ConfigError naming both when `other_period_s` (described by `other`, e.g.
// "sampc.yaml: sampc.control_period_s") is not the mission's control period: the control
// period is one, and a copy that disagrees shifts SAMPC's warm start by the wrong time or
// ticks the simulator at another rate than the agents step.
void check_control_period(const MissionParams& mission, double other_period_s,
                          const std::string& other);

}  // namespace cover::mission
