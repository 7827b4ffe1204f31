#include "cover/mission/failsafe_ladder.hpp"

#include <algorithm>
#include <cmath>

namespace cover::mission {

namespace {

bool state_finite(const model::RelativeState& m) {
  return std::isfinite(m.stamp_s) && m.position_m.allFinite() && m.velocity_m_s.allFinite() &&
         m.attitude.coeffs().allFinite() && m.attitude.norm() > 0.5;
}

InputHealth problem(FailsafeCause cause, double age_s, bool state_usable) {
  InputHealth health;
  health.cause = cause;
  health.age_s = std::isfinite(age_s) ? age_s : 0.0;
  health.state_usable = state_usable;
  return health;
}

}  // namespace

InputHealth assess_inputs(const LadderInput& input, double now_s, const MissionParams& params) {
  if (!std::isfinite(now_s)) return problem(FailsafeCause::ClockInvalid, 0.0, false);
  if (!input.has_state || input.state == nullptr) {
    return problem(FailsafeCause::StateMissing, 0.0, false);
  }
  if (!state_finite(*input.state)) return problem(FailsafeCause::StateInvalid, 0.0, false);
  const double state_age_s = now_s - input.state->stamp_s;
  if (state_age_s > params.state_timeout_s) {
    return problem(FailsafeCause::StateStale, state_age_s, false);
  }
  if (!input.has_imu || input.imu == nullptr) {
    return problem(FailsafeCause::ImuMissing, 0.0, true);
  }
  if (!input.imu->all_finite() || !std::isfinite(input.imu_stamp_s)) {
    return problem(FailsafeCause::ImuInvalid, 0.0, true);
  }
  const double imu_age_s = now_s - input.imu_stamp_s;
  if (imu_age_s > params.imu_timeout_s) {
    InputHealth health = problem(FailsafeCause::ImuStale, imu_age_s, true);
    health.imu_held = imu_age_s <= params.imu_timeout_s + params.imu_hold_s;
    return health;
  }
  InputHealth fresh;
  fresh.state_usable = true;
  return fresh;
}

FailsafeLadder::FailsafeLadder(const MissionParams& params) : params_(params) {}

LadderLevel FailsafeLadder::update(const InputHealth& health, double now_s) {
  changed_ = false;
  resumed_ = false;
  if (level_ == LadderLevel::EmergencyLanding || level_ == LadderLevel::Disarmed) return level_;
  if (health.cause == FailsafeCause::None) {
    // Back to SAMPC: after a hover the stage must be replanned from where the UAV is.
    resumed_ = level_ == LadderLevel::EmergencyHover;
    if (level_ != LadderLevel::Nominal) climb_to(LadderLevel::Nominal, now_s);
    return level_;
  }
  if (health.imu_held && level_ != LadderLevel::EmergencyHover) {
    if (level_ != LadderLevel::ImuHold) {
      cause_ = health.cause;
      cause_age_s_ = health.age_s;
      climb_to(LadderLevel::ImuHold, now_s);
    }
    return level_;
  }
  if (level_ == LadderLevel::Nominal || level_ == LadderLevel::ImuHold) {
    cause_ = health.cause;
    cause_age_s_ = health.age_s;
    climb_to(LadderLevel::EmergencyHover, now_s);
  } else if (std::isfinite(now_s) && now_s - level_since_s_ >= params_.emergency_hover_s) {
    climb_to(LadderLevel::EmergencyLanding, now_s);
  }
  return level_;
}

void FailsafeLadder::climb_to(LadderLevel level, double now_s) {
  changed_ = true;
  level_ = level;
  // An invalid clock keeps the previous time: the hover's duration then counts from there.
  if (std::isfinite(now_s)) level_since_s_ = now_s;
  if (level == LadderLevel::EmergencyHover) {
    // Hold the height the UAV was last known at; the integral starts anew each episode.
    reference_start_height_m_ = height_m_;
    height_integral_m_s2_ = 0.0;
  }
  if (level == LadderLevel::EmergencyLanding) {
    reference_start_height_m_ = height_m_;
    touchdown_since_s_ = -1.0;
  }
}

void FailsafeLadder::remember(const model::RelativeState& state, double hover_thrust_m_s2,
                              const ControlCommand& sent, double now_s) {
  const double up = (state.attitude.normalized() * Eigen::Vector3d::UnitZ()).z();
  hover_estimate_.add(now_s, state.position_m.z(), state.velocity_m_s.z(),
                      sent.armed ? sent.thrust_m_s2 * up : 0.0, params_.control_period_s);
  const double hover = hover_estimate_.valid() ? hover_estimate_.value_m_s2() : hover_thrust_m_s2;
  if (std::isfinite(hover)) {
    hover_thrust_m_s2_ = std::clamp(hover, 0.5 * model::kGravity_m_s2, 1.5 * model::kGravity_m_s2);
  }
  last_command_ = sent;
  set_estimate(state, now_s);
}

void FailsafeLadder::set_estimate(const model::RelativeState& state, double now_s) {
  attitude_ = state.attitude.normalized();
  height_m_ = state.position_m.z();
  vertical_speed_m_s_ = state.velocity_m_s.z();
  estimate_time_s_ = now_s;
}

void FailsafeLadder::dead_reckon(const model::RelativeState* state, double now_s) {
  if (state != nullptr) {
    set_estimate(*state, now_s);
    return;
  }
  double dt_s = params_.control_period_s;
  if (std::isfinite(now_s) && estimate_time_s_ >= 0.0) {
    dt_s = std::clamp(now_s - estimate_time_s_, 0.0, 0.1);
  }
  // The flight controller tracks the commanded rates: the attitude follows them, and the
  // thrust along the body z axis against the hover thrust gives the vertical acceleration.
  const Eigen::Vector3d rotation = last_command_.body_rate_rad_s * dt_s;
  if (rotation.norm() > 0.0) {
    attitude_ =
        (attitude_ * Eigen::Quaterniond(Eigen::AngleAxisd(rotation.norm(), rotation.normalized())))
            .normalized();
  }
  const double up = (attitude_ * Eigen::Vector3d::UnitZ()).z();
  const double thrust = last_command_.armed ? last_command_.thrust_m_s2 : 0.0;
  const double accel_m_s2 = model::kGravity_m_s2 * (thrust * up / hover_thrust_m_s2_ - 1.0);
  height_m_ += vertical_speed_m_s_ * dt_s + 0.5 * accel_m_s2 * dt_s * dt_s;
  vertical_speed_m_s_ += accel_m_s2 * dt_s;
  if (std::isfinite(now_s)) estimate_time_s_ = now_s;
}

double FailsafeLadder::reference_height_m(double now_s) const {
  if (level_ != LadderLevel::EmergencyLanding) return reference_start_height_m_;
  return reference_start_height_m_ - params_.emergency_descent_rate_m_s * (now_s - level_since_s_);
}

// Thrust along the frame's up that tracks the vertical reference: PID on the height with
// the reference's speed as feed-forward, around the hover thrust. The integral learns only
// from a measured height; blind, it keeps what it had learnt.
double FailsafeLadder::vertical_thrust_m_s2(bool measured, double now_s) {
  const double reference_speed_m_s =
      level_ == LadderLevel::EmergencyLanding ? -params_.emergency_descent_rate_m_s : 0.0;
  const double error_m = reference_height_m(now_s) - height_m_;
  if (measured && std::isfinite(error_m)) {
    const double limit_m_s2 = params_.emergency_integral_limit_m_s2;
    height_integral_m_s2_ =
        std::clamp(height_integral_m_s2_ +
                       params_.emergency_integral_gain_1_s3 * error_m * params_.control_period_s,
                   -limit_m_s2, limit_m_s2);
  }
  const double accel_m_s2 =
      params_.emergency_height_gain_1_s2 * error_m +
      params_.emergency_speed_gain_1_s * (reference_speed_m_s - vertical_speed_m_s_) +
      height_integral_m_s2_;
  const double thrust_m_s2 = hover_thrust_m_s2_ * (1.0 + accel_m_s2 / model::kGravity_m_s2);
  // A blind landing may slow its sink but never push up: on the ground (which it cannot
  // see) more than the hover thrust would lift it off again.
  if (!measured && level_ == LadderLevel::EmergencyLanding) {
    return std::min(thrust_m_s2, hover_thrust_m_s2_);
  }
  return thrust_m_s2;
}

bool FailsafeLadder::touched_down(const model::RelativeState* state, double now_s) {
  const double reference_m = reference_height_m(now_s);
  // Measured: something holds the UAV above its sinking reference. Blind: the reference is
  // below the lowest ground the frame can have, so contact has certainly been made.
  const bool held_up =
      state != nullptr ? state->position_m.z() - reference_m > params_.land_detect_gap_m &&
                             std::abs(state->velocity_m_s.z()) < params_.land_detect_speed_m_s
                       : reference_m < -params_.emergency_blind_floor_m - params_.land_detect_gap_m;
  if (!held_up) {
    touchdown_since_s_ = -1.0;
    return false;
  }
  if (touchdown_since_s_ < 0.0) touchdown_since_s_ = now_s;
  return now_s - touchdown_since_s_ >= params_.land_detect_time_s;
}

ControlCommand FailsafeLadder::command(const model::RelativeState* state, double now_s) {
  dead_reckon(state, now_s);
  const double t_s = std::isfinite(now_s) ? now_s : estimate_time_s_;
  if (level_ == LadderLevel::EmergencyLanding && touched_down(state, t_s)) {
    climb_to(LadderLevel::Disarmed, t_s);
  }
  // Blind, the descent's height is a guess that integrates the hover thrust's error; the
  // flight controller senses its own height, so it lands the UAV from here on.
  if (level_ == LadderLevel::EmergencyLanding && state == nullptr) handed_over_ = true;
  ControlCommand command;
  command.handover = handed_over_;
  if (level_ == LadderLevel::Disarmed) {
    last_command_ = command;
    return command;
  }
  // Level: turn the body z axis toward the frame's up (the frames are level), no yaw.
  const Eigen::Vector3d up_in_body = attitude_.inverse() * Eigen::Vector3d::UnitZ();
  Eigen::Vector3d rates =
      params_.emergency_level_gain_1_s * Eigen::Vector3d::UnitZ().cross(up_in_body);
  const double max_rate_rad_s = 2.0;
  if (rates.norm() > max_rate_rad_s) rates *= max_rate_rad_s / rates.norm();
  // Height held (hover) or sinking along a line (landing), on the hover thrust.
  const double tilt_cos = std::max((attitude_ * Eigen::Vector3d::UnitZ()).z(), 0.7);
  const double thrust = vertical_thrust_m_s2(state != nullptr, t_s) / tilt_cos;
  command.thrust_m_s2 = std::clamp(thrust, 0.5 * hover_thrust_m_s2_, 1.5 * hover_thrust_m_s2_);
  command.body_rate_rad_s = rates;
  command.armed = true;
  last_command_ = command;
  return command;
}

}  // namespace cover::mission
