#pragma once

#include <Eigen/Core>
#include <array>

#include "cover/sampc/horizon_reference.hpp"
#include "cover/sampc/intercept_velocity.hpp"
#include "cover/sampc/sampc_params.hpp"
#include "cover/vocabulary/state.hpp"

namespace cover::sampc {

// The two reference modes of sec. 4.3.
enum class ReferenceMode {
  XyzRef,  // x-y-z-ref: track the planned position, velocity, nose along the UGV's x
  XyZRef,  // xy-z-ref: track height and squared horizontal distance, customised velocity
};

// Which reference mode `mode` uses at `stage` (Cover and NoRefVxy adapt; ConiMpc does not).
ReferenceMode reference_mode_for(Mode mode, model::Stage stage);

// The nonlinear least-squares cost of one node k (eq. 24, docs/model.md):
//   sum_i wp_i (p - p_ref)_i^2 + sum_i wv_i (v - v_ref)_i^2 + sum_i wq_i e_i^2
//   + wd (px^2 + py^2 - d_ref)^2 + sum_i wu_i (u - u_h)_i^2
// with the attitude error e = q - (q . q_ref) q_ref, the part of q orthogonal to q_ref:
// e(-q) = -e(q), so q and -q cost the same; it is linear in q (exact Gauss-Newton) and
// |e|^2 = sin^2(angle/2), which matches |q - q_ref|^2 to second order near the reference.
// The terminal node has zero input weights.
struct NodeCost {
  Eigen::Vector3d position_ref_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d position_weight = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_ref_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_weight = Eigen::Vector3d::Zero();
  Eigen::Vector4d attitude_ref{1.0, 0.0, 0.0, 0.0};
  Eigen::Vector4d attitude_weight = Eigen::Vector4d::Zero();
  double squared_distance_ref_m2 = 0.0;
  double squared_distance_weight = 0.0;
  model::Input input_ref = model::hover_input();
  model::Input input_weight = model::Input::Zero();
  // Node 0 only (zero elsewhere): + sum_i wr_i (u - u_prev)_i^2, what leaving the command
  // handed out at the previous control step costs (after a frame switch, throughout an
  // xy-z-ref transition). Part of the node's cost so that HorizonCost is the whole
  // objective: the NLopt reference (reference_solver.hpp) solves the same problem as SAMPC.
  model::Input input_rate_weight = model::Input::Zero();
  model::Input previous_input = model::hover_input();

  // d e / d q = I - q_ref q_ref' (constant: e is linear in q).
  Eigen::Matrix4d attitude_error_jacobian() const;

  // Cost value at (x, u); adds its gradient into the optional outputs.
  double evaluate(const model::UavState& x, const model::Input& u,
                  model::UavState* grad_x = nullptr, model::Input* grad_u = nullptr) const;
};

// The start of the rate-limited yaw reference, carried from one control step to the next.
struct YawTrack {
  bool valid = false;       // false: start at the measured yaw (first solve, frame switch)
  double anchor_rad = 0.0;  // yaw reference of node 0
  int turn_sign = 0;        // +1 turning left, -1 right, 0 aligned with the target
};

// The whole horizon's costs for one solve: references and stage-adaptive weights.
struct HorizonCost {
  int horizon_steps = 0;
  ReferenceMode reference_mode = ReferenceMode::XyzRef;
  // The target yaw the reference turns toward (xy-z-ref: nose at the UGV), for holding it
  // near the UGV axis.
  double yaw_ref_rad = 0.0;
  // The yaw reference's start and turn direction, for the next control step's build.
  YawTrack yaw_track;
  // Mode intercept at the transition stage: the law at the measured position (node 0),
  // with its fallback reason; default (no fallback, tau 0) otherwise.
  InterceptVelocity intercept;
  std::array<NodeCost, kMaxHorizon + 1> nodes;
};

// Builds the references and weights of eqs. 25-35 for `input` (the UAV state is the
// measurement: d0, the eq. 30 velocity and the yaw reference depend on it). `held_yaw_rad`
// is used as yaw reference when the UAV is within yaw_hold_radius_m of the UGV's axis.
// `previous_yaw` is the yaw_track of the previous control step, `elapsed_s` the time since
// it: the yaw reference moves on from there at the configured rate (default: start at the
// measured yaw). `predicted_states` (horizon_steps + 1 entries, or null) is the solver's
// warm start: the free nodes that carry eq. 30 evaluate it at their own predicted
// position (null: at the measured one). `intercept_lead_fraction` in [0, 1] scales the
// intercept law's departure from eq. 30 (Sampc ramps it in after a frame switch).
void build_horizon_cost(const SampcParams& params, const SampcInput& input, double held_yaw_rad,
                        HorizonCost& cost, const YawTrack& previous_yaw = {},
                        double elapsed_s = 0.0, const model::UavState* predicted_states = nullptr,
                        double intercept_lead_fraction = 1.0);

}  // namespace cover::sampc
