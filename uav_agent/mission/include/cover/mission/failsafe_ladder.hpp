#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "cover/mission/failsafe_ladder_hover_thrust.hpp"
#include "cover/mission/ladder_level.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/vocabulary/control_command.hpp"
#include "cover/vocabulary/failsafe_cause.hpp"
#include "cover/vocabulary/relative_state.hpp"
#include "cover/vocabulary/state.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::mission {

// The reference frame's inputs on one step, judged against the timeouts.
struct InputHealth {
  FailsafeCause cause = FailsafeCause::None;  // None: all fresh
  double age_s = 0.0;                         // age of the input `cause` names (0 when it has none)
  bool state_usable = false;  // the relative state is fresh and finite (feedback for the ladder)
  bool imu_held = false;      // the only problem is an IMU still within imu_hold_s
};

struct LadderInput {
  bool has_state = false;
  const model::RelativeState* state = nullptr;
  bool has_imu = false;
  double imu_stamp_s = 0.0;
  const model::UgvMotion* imu = nullptr;
};

InputHealth assess_inputs(const LadderInput& input, double now_s, const MissionParams& params);

// The UAV agent's failsafes for a lost or invalid reference input (docs/failsafes.md): the
// last IMU held briefly, then emergency hover (level attitude, the last hover thrust),
// after emergency_hover_s an emergency landing (level, sinking at
// emergency_descent_rate_m_s) that disarms on contact. Data back during the hover returns
// to Nominal (`resumed()`: the caller replans the stage). Without a relative state the
// attitude and vertical speed are dead-reckoned from the commands since the last one.
class FailsafeLadder {
 public:
  explicit FailsafeLadder(const MissionParams& params);

  // Climbs or leaves the ladder on this step's health. `changed()` is true on the step
  // where the level changed.
  LadderLevel update(const InputHealth& health, double now_s);
  // On every nominal step: the state, the hover thrust SAMPC's estimate implies, and the
  // command sent (the dead reckoning's start).
  void remember(const model::RelativeState& state, double hover_thrust_m_s2,
                const ControlCommand& sent, double now_s);
  // The emergency command of the current level (EmergencyHover or EmergencyLanding);
  // `state` is the reference frame's relative state when usable, else nullptr.
  ControlCommand command(const model::RelativeState* state, double now_s);

  LadderLevel level() const { return level_; }
  bool changed() const { return changed_; }
  bool resumed() const { return resumed_; }       // left EmergencyHover for Nominal this step
  FailsafeCause cause() const { return cause_; }  // of the current (or last) climb
  double cause_age_s() const { return cause_age_s_; }
  double hover_thrust_m_s2() const { return hover_thrust_m_s2_; }
  // An emergency landing has had to go on blind: every command since hands the UAV over
  // to the flight controller's landing (ControlCommand::handover). Latched with the landing.
  bool handed_over() const { return handed_over_; }

 private:
  void climb_to(LadderLevel level, double now_s);
  void set_estimate(const model::RelativeState& state, double now_s);
  void dead_reckon(const model::RelativeState* state, double now_s);
  bool touched_down(const model::RelativeState* state, double now_s);
  double reference_height_m(double now_s) const;
  double vertical_thrust_m_s2(bool measured, double now_s);

  MissionParams params_;
  LadderLevel level_ = LadderLevel::Nominal;
  bool changed_ = false;
  bool resumed_ = false;
  FailsafeCause cause_ = FailsafeCause::None;
  double cause_age_s_ = 0.0;
  double level_since_s_ = 0.0;
  double hover_thrust_m_s2_ = model::kGravity_m_s2;
  // The UAV's attitude in the reference frame and its height and vertical speed there:
  // measured when available, else propagated from the commands.
  Eigen::Quaterniond attitude_ = Eigen::Quaterniond::Identity();
  double height_m_ = 0.0;
  double vertical_speed_m_s_ = 0.0;
  double estimate_time_s_ = -1.0;  // < 0: nothing remembered yet
  ControlCommand last_command_;
  // The vertical reference (a held height in the hover, a line sinking at the descent
  // rate in the landing) and the integral of its error, which absorbs what the hover
  // thrust estimate still misses while a relative state is there to measure it.
  double reference_start_height_m_ = 0.0;
  double height_integral_m_s2_ = 0.0;
  HoverThrustEstimate hover_estimate_;
  double touchdown_since_s_ = -1.0;
  bool handed_over_ = false;
};

}  // namespace cover::mission
