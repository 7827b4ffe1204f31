#pragma once

#include <Eigen/Core>
#include <vector>

#include "cover/model/dynamics.hpp"

namespace cover::mission {

// Estimates the acceleration the SAMPC model misses (drag, mass error, a lagging UGV IMU)
// from the velocity it predicted against the velocity measured, over a sliding window:
//
//   d = (v(t) - v(t - T) - sum of the model's predicted velocity changes) / T.
//
// One control period's velocity change (~mm/s) drowns in the velocity noise (~1 cm/s); over
// a window T of tens of steps the noise divides by T. Unlike an integral of the position
// error it needs no position reference, so it also learns at the transition stage
// (xy-z-ref), and the final stage starts with the disturbance of its frame already known.
// The estimate is then low-passed. Frames differ (drag depends on the frame's motion):
// reset() at each frame switch.
class DisturbanceObserver {
 public:
  // window_steps >= 1 control periods of period_s; filter_time_constant_s >= 0.
  DisturbanceObserver(int window_steps, double period_s, double filter_time_constant_s);

  // One control step: the measured state and the UGV motion now (as SAMPC sees it, the
  // current estimate already subtracted), and the command applied from now on. Returns the
  // estimate (zero until a window has filled).
  const Eigen::Vector3d& update(const model::UavState& state, const model::UgvMotion& ugv,
                                const model::Input& command);

  void reset();
  const Eigen::Vector3d& estimate_m_s2() const { return estimate_m_s2_; }
  bool ready() const { return ready_; }

 private:
  int window_steps_;
  double period_s_;
  double filter_gain_;  // per step, from the time constant
  // Ring buffers over the window: measured velocity and the model's predicted velocity
  // change for the step that started at that sample.
  std::vector<Eigen::Vector3d> velocity_m_s_;
  std::vector<Eigen::Vector3d> predicted_change_m_s_;
  Eigen::Vector3d predicted_change_sum_m_s_ = Eigen::Vector3d::Zero();
  int next_ = 0;
  int samples_ = 0;
  bool has_previous_ = false;
  model::UavState previous_state_;
  model::UgvMotion previous_ugv_;
  model::Input previous_command_;
  Eigen::Vector3d estimate_m_s2_ = Eigen::Vector3d::Zero();
  bool ready_ = false;
};

}  // namespace cover::mission
