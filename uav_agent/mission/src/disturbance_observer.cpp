#include "cover/mission/disturbance_observer.hpp"

#include <algorithm>
#include <cmath>

namespace cover::mission {

using model::idx::kVelocity;

DisturbanceObserver::DisturbanceObserver(int window_steps, double period_s,
                                         double filter_time_constant_s)
    : window_steps_(std::max(1, window_steps)),
      period_s_(period_s),
      filter_gain_(filter_time_constant_s > 0.0 ? 1.0 - std::exp(-period_s / filter_time_constant_s)
                                                : 1.0),
      velocity_m_s_(static_cast<std::size_t>(window_steps_) + 1, Eigen::Vector3d::Zero()),
      predicted_change_m_s_(static_cast<std::size_t>(window_steps_) + 1, Eigen::Vector3d::Zero()) {}

void DisturbanceObserver::reset() {
  predicted_change_sum_m_s_.setZero();
  next_ = 0;
  samples_ = 0;
  has_previous_ = false;
  ready_ = false;
  estimate_m_s2_.setZero();
}

const Eigen::Vector3d& DisturbanceObserver::update(const model::UavState& state,
                                                   const model::UgvMotion& ugv,
                                                   const model::Input& command) {
  const int size = window_steps_ + 1;
  if (!state.allFinite() || !ugv.all_finite() || !command.allFinite()) {
    reset();  // a gap: the window no longer describes consecutive steps
    return estimate_m_s2_;
  }
  // The model's velocity change over the step just ended, from the previous measurement
  // and command. The model already contains the current estimate (through ugv), so the
  // window measures what is still missing on top of it: hence the increment below.
  Eigen::Vector3d predicted_change = Eigen::Vector3d::Zero();
  if (has_previous_) {
    const model::UavState predicted =
        model::uav_rk4_step(previous_state_, previous_command_, previous_ugv_, period_s_);
    predicted_change = predicted.segment<3>(kVelocity) - previous_state_.segment<3>(kVelocity);
  }
  // Slot `next_` receives this sample; the sum covers the changes between the oldest and
  // the newest velocity in the window.
  if (samples_ == size) predicted_change_sum_m_s_ -= predicted_change_m_s_[(next_ + 1) % size];
  velocity_m_s_[next_] = state.segment<3>(kVelocity);
  predicted_change_m_s_[next_] = predicted_change;
  if (samples_ > 0) predicted_change_sum_m_s_ += predicted_change;
  const int oldest = samples_ == size ? (next_ + 1) % size : 0;
  samples_ = std::min(samples_ + 1, size);
  next_ = (next_ + 1) % size;

  previous_state_ = state;
  previous_ugv_ = ugv;
  previous_command_ = command;
  has_previous_ = true;

  if (samples_ < size) return estimate_m_s2_;
  const double window_s = window_steps_ * period_s_;
  const Eigen::Vector3d measured_change = state.segment<3>(kVelocity) - velocity_m_s_[oldest];
  const Eigen::Vector3d missing_m_s2 = (measured_change - predicted_change_sum_m_s_) / window_s;
  estimate_m_s2_ += filter_gain_ * missing_m_s2;
  ready_ = true;
  return estimate_m_s2_;
}

}  // namespace cover::mission
