#pragma once

#include <Eigen/Core>
#include <array>

#include "cover/sampc/sampc_params.hpp"
#include "cover/vocabulary/stage.hpp"
#include "cover/vocabulary/state.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::sampc {

// The stage's planned trajectory sampled over the horizon, in the reference UGV frame:
// entry k is the reference at t + k * step_s, for k = 0..horizon_steps (entries beyond the
// configured horizon are ignored). Filled by the caller (mission layer) from the planner.
struct HorizonReference {
  std::array<Eigen::Vector3d, kMaxHorizon + 1> position_m;
  std::array<Eigen::Vector3d, kMaxHorizon + 1> velocity_m_s;
  // The plan's acceleration: x-y-z-ref turns it into each node's thrust and attitude
  // reference (SampcParams::tracking_feed_forward).
  std::array<Eigen::Vector3d, kMaxHorizon + 1> acceleration_m_s2;

  // Every entry equal to a still point: hold position there.
  static HorizonReference hold(const Eigen::Vector3d& position_m) {
    HorizonReference r;
    r.position_m.fill(position_m);
    r.velocity_m_s.fill(Eigen::Vector3d::Zero());
    r.acceleration_m_s2.fill(Eigen::Vector3d::Zero());
    return r;
  }
};

// Everything one SAMPC call needs, all in the current reference UGV frame G_k.
struct SampcInput {
  model::Stage stage = model::Stage::Initial;
  model::UavState uav_state = model::uav_state_at_rest(Eigen::Vector3d::Zero());  // p v q
  model::UgvMotion ugv;
  HorizonReference reference = HorizonReference::hold(Eigen::Vector3d::Zero());
  // The task's UAV speed limit relative to the reference frame (m/s): the intercept law
  // keeps its velocity relative to the UGV's translation within it.
  double speed_limit_m_s = 1.0;
};

}  // namespace cover::sampc
