#include "cover/sampc/horizon_cost.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cover/model/quaternion.hpp"
#include "cover/vocabulary/angles.hpp"

namespace cover::sampc {

using model::idx::kPosition;
using model::idx::kQuaternion;
using model::idx::kVelocity;

ReferenceMode reference_mode_for(Mode mode, model::Stage stage) {
  if (mode == Mode::ConiMpc) return ReferenceMode::XyzRef;
  return stage == model::Stage::Transition ? ReferenceMode::XyZRef : ReferenceMode::XyzRef;
}

Eigen::Matrix4d NodeCost::attitude_error_jacobian() const {
  return Eigen::Matrix4d::Identity() - attitude_ref * attitude_ref.transpose();
}

double NodeCost::evaluate(const model::UavState& x, const model::Input& u, model::UavState* grad_x,
                          model::Input* grad_u) const {
  const Eigen::Vector3d position_error = x.segment<3>(kPosition) - position_ref_m;
  const Eigen::Vector3d velocity_error = x.segment<3>(kVelocity) - velocity_ref_m_s;
  // The part of q orthogonal to q_ref: odd in q, so q and -q (the same attitude) cost the
  // same, and smooth everywhere (unlike choosing the nearer of +-q_ref, whose switch makes
  // the SQP chatter when the yaw error nears 180 deg). |e|^2 = sin^2(angle / 2).
  const Eigen::Matrix4d projector = attitude_error_jacobian();
  const Eigen::Vector4d attitude_error = projector * x.segment<4>(kQuaternion);
  const double distance_error =
      x(kPosition) * x(kPosition) + x(kPosition + 1) * x(kPosition + 1) - squared_distance_ref_m2;
  const model::Input input_error = u - input_ref;

  if (grad_x != nullptr) {
    grad_x->segment<3>(kPosition) += 2.0 * position_weight.cwiseProduct(position_error);
    grad_x->segment<3>(kVelocity) += 2.0 * velocity_weight.cwiseProduct(velocity_error);
    grad_x->segment<4>(kQuaternion) +=
        2.0 * projector * attitude_weight.cwiseProduct(attitude_error);
    const double scale = 4.0 * squared_distance_weight * distance_error;
    (*grad_x)(kPosition) += scale * x(kPosition);
    (*grad_x)(kPosition + 1) += scale * x(kPosition + 1);
  }
  if (grad_u != nullptr) *grad_u += 2.0 * input_weight.cwiseProduct(input_error);

  double value = position_weight.dot(position_error.cwiseAbs2()) +
                 velocity_weight.dot(velocity_error.cwiseAbs2()) +
                 attitude_weight.dot(attitude_error.cwiseAbs2()) +
                 squared_distance_weight * distance_error * distance_error +
                 input_weight.dot(input_error.cwiseAbs2());
  if ((input_rate_weight.array() > 0.0).any()) {
    const model::Input change = u - previous_input;
    if (grad_u != nullptr) *grad_u += 2.0 * input_rate_weight.cwiseProduct(change);
    value += input_rate_weight.dot(change.cwiseAbs2());
  }
  return value;
}

namespace {

double wrapped_angle(double angle_rad) {
  return std::remainder(angle_rad, model::kTwoPi);  // in [-pi, pi]
}

// Yaw of the UAV in the reference frame, from its attitude quaternion [w, x, y, z].
double measured_yaw(const model::UavState& x) {
  const Eigen::Vector4d q = x.segment<4>(kQuaternion);
  return std::atan2(2.0 * (q(0) * q(3) + q(1) * q(2)), 1.0 - 2.0 * (q(2) * q(2) + q(3) * q(3)));
}

// Which way the yaw reference turns: the shorter way round, except that a turn in progress
// keeps its direction until the other way is shorter by more than yaw_flip_hysteresis_rad.
// When the target moves faster than the UAV can turn (a UGV turning hard rotates the frame),
// the error drifts through 180 deg; flipping the turn there reverses the whole yaw plan in
// one control step.
double yaw_error_to_target(const SampcParams& params, double from_yaw_rad, double target_yaw_rad,
                           int turn_sign) {
  double error = wrapped_angle(target_yaw_rad - from_yaw_rad);
  if (turn_sign * error < 0.0 && std::abs(error) > model::kPi - params.yaw_flip_hysteresis_rad) {
    error += turn_sign * model::kTwoPi;
  }
  return error;
}

int turn_sign_of(double yaw_error_rad) {
  constexpr double kAlignedYaw_rad = 0.05;  // closer than this: no turn in progress
  if (std::abs(yaw_error_rad) < kAlignedYaw_rad) return 0;
  return yaw_error_rad > 0.0 ? 1 : -1;
}

// The yaw reference is a rate-limited trajectory toward the stage's target yaw (nose at the
// UGV, or the UGV's x axis): its start (the anchor) moves at most yaw_reference_rate_rad_s
// per elapsed second, stays within yaw_reference_max_lag_rad of the measured yaw, and node k
// lies at most rate * k * dt further on. A step to the target would, after a frame switch,
// ask for up to 180 deg at once (a thrust and body-rate spike); re-starting it at the
// measured yaw every step instead would leave almost no pull (the error at node 1 is tiny).
struct YawPlan {
  YawTrack track;        // the anchor (node 0's yaw) and the turn direction
  double error_rad = 0;  // from the anchor to the target, the way the reference turns
};

YawPlan plan_yaw(const SampcParams& params, const SampcInput& input, double target_yaw_rad,
                 const YawTrack& previous, double elapsed_s) {
  const double measured = measured_yaw(input.uav_state);
  YawPlan plan;
  plan.track.valid = true;
  plan.track.anchor_rad = measured;
  if (previous.valid) {
    const double error =
        yaw_error_to_target(params, previous.anchor_rad, target_yaw_rad, previous.turn_sign);
    const double step = params.yaw_reference_rate_rad_s * elapsed_s;
    const double anchor = previous.anchor_rad + std::clamp(error, -step, step);
    const double lag =
        std::clamp(wrapped_angle(anchor - measured), -params.yaw_reference_max_lag_rad,
                   params.yaw_reference_max_lag_rad);
    plan.track.anchor_rad = measured + lag;
  }
  plan.error_rad =
      yaw_error_to_target(params, plan.track.anchor_rad, target_yaw_rad, previous.turn_sign);
  plan.track.turn_sign = turn_sign_of(plan.error_rad);
  return plan;
}

Eigen::Vector4d yaw_reference(const SampcParams& params, const YawPlan& plan, int k) {
  const double reachable = params.yaw_reference_rate_rad_s * params.step_s * k;
  return model::yaw_quaternion(plan.track.anchor_rad +
                               std::clamp(plan.error_rad, -reachable, reachable));
}

// The thrust and attitude that fly the reference's acceleration at node k: the model's
// v' = -beta x p - 2 Omega x v - Omega x (Omega x p) + R(q) [0, 0, F] - a solved for the
// thrust vector at the reference's p, v and v', R(q) tilting the yaw reference's body z
// onto it. A level hover reference instead makes every planned acceleration cost attitude
// and thrust error, so the UAV lags each one (Scenario 2's braking descent: 3.6 cm in x).
// Keeps the hover reference when the thrust vector is beyond the input box or points down.
void add_feed_forward(const SampcParams& params, const SampcInput& input, int k, NodeCost& node) {
  const model::UgvMotion ugv = input.ugv.advanced(k * params.step_s);
  const Eigen::Vector3d& w = ugv.angular_velocity_rad_s;
  const Eigen::Vector3d& p = input.reference.position_m[k];
  const Eigen::Vector3d& v = input.reference.velocity_m_s[k];
  const Eigen::Vector3d thrust = input.reference.acceleration_m_s2[k] +
                                 ugv.angular_acceleration_rad_s2.cross(p) + 2.0 * w.cross(v) +
                                 w.cross(w.cross(p)) + ugv.specific_force_m_s2;
  const double magnitude = thrust.norm();
  if (!(magnitude >= params.thrust_min_m_s2 && magnitude <= params.thrust_max_m_s2) ||
      thrust.z() <= 0.0) {
    return;
  }
  // The shortest rotation from z onto the thrust direction n: [1 + z.n, z x n], normalised.
  const Eigen::Vector3d n = thrust / magnitude;
  const Eigen::Vector4d tilt = Eigen::Vector4d(1.0 + n.z(), -n.y(), n.x(), 0.0).normalized();
  node.attitude_ref = model::multiply(tilt, node.attitude_ref);
  node.input_ref(model::input_idx::kThrust) = magnitude;
}

// The body rates that turn node k's attitude reference into node k + 1's over one step,
// the frame's own rotation included (q' = 1/2 q (x) [0, w] - 1/2 [0, Omega] (x) q): with a
// zero rate reference, every turn of the reference (a tilt for the plan's acceleration, the
// yaw reference's turn) costs input error and the UAV lags it.
void add_rate_feed_forward(const SampcParams& params, const SampcInput& input, int k,
                           HorizonCost& cost) {
  NodeCost& node = cost.nodes[k];
  const Eigen::Vector4d& q = node.attitude_ref;
  const Eigen::Vector4d conjugate(q(0), -q(1), -q(2), -q(3));
  Eigen::Vector4d delta = model::multiply(conjugate, cost.nodes[k + 1].attitude_ref);
  if (delta(0) < 0.0) delta = -delta;  // q and -q: the short way round
  const Eigen::Vector3d frame_rate = input.ugv.advanced(k * params.step_s).angular_velocity_rad_s;
  const Eigen::Vector3d rate =
      2.0 * delta.tail<3>() / params.step_s + model::rotation_matrix(q).transpose() * frame_rate;
  const model::Input lower = params.input_lower_bound();
  const model::Input upper = params.input_upper_bound();
  for (int i = 0; i < 3; ++i) {
    node.input_ref(1 + i) = std::clamp(rate(i), lower(1 + i), upper(1 + i));
  }
}

// x-y-z-ref (eqs. 25-27 with the initial/final weights): follow the plan in full, nose
// turning toward the UGV's x axis.
void build_tracking_cost(const SampcParams& params, const SampcInput& input,
                         const YawTrack& previous_yaw, double elapsed_s, HorizonCost& cost) {
  const WeightSet& w = params.tracking_weights;
  const YawPlan yaw = plan_yaw(params, input, 0.0, previous_yaw, elapsed_s);
  // Not at coni-mpc's transition stage: that is the prior method as published, the
  // baseline the benchmarks compare against.
  const bool feed_forward = params.tracking_feed_forward && input.stage != model::Stage::Transition;
  for (int k = 0; k <= params.horizon_steps; ++k) {
    NodeCost& node = cost.nodes[k];
    const double state_decay = std::exp(-params.e0 * k);
    node.position_ref_m = input.reference.position_m[k];
    node.position_weight = state_decay * w.position;
    node.velocity_ref_m_s = input.reference.velocity_m_s[k];
    node.velocity_weight = state_decay * w.velocity;
    node.attitude_ref = yaw_reference(params, yaw, k);
    node.attitude_weight = state_decay * w.attitude;
    node.squared_distance_ref_m2 = 0.0;
    node.squared_distance_weight = 0.0;
    node.input_ref = model::hover_input();
    node.input_weight = std::exp(-params.e3 * k) * w.input;
    if (feed_forward) add_feed_forward(params, input, k, node);
  }
  if (feed_forward) {
    for (int k = 0; k < params.horizon_steps; ++k) add_rate_feed_forward(params, input, k, cost);
  }
  cost.yaw_ref_rad = 0.0;
  cost.yaw_track = yaw.track;
}

// Eq. 30 at position `p`: cancel the frame-rotation-induced motion and head at the UGV's
// axis at the plan's horizontal speed. On the axis the direction is undefined: rotation
// part only.
Eigen::Vector2d eq30_velocity(const SampcParams& params, const Eigen::Vector3d& angular_velocity,
                              const Eigen::Vector3d& p, double speed_xy) {
  Eigen::Vector2d velocity = -angular_velocity.cross(p).head<2>();
  const double horizontal_distance = p.head<2>().norm();
  if (horizontal_distance > params.yaw_hold_radius_m) {
    velocity -= p.head<2>() / horizontal_distance * speed_xy;
  }
  return velocity;
}

// A transition velocity reference (eq. 30's, or intercept's) at node k as far as the UAV
// can get there: eq. 30 asks for its velocity at once,
// and at a frame switch it can be 2 m/s from the UAV's (the velocity of the UGV it left).
// The UAV's velocity relative to the UGV's translation (v + Omega x p) moves toward eq. 30's
// by at most eq30_acceleration_limit_m_s2 * k * dt at node k, so the horizon asks for a
// change the UAV can make instead of an attitude step at the first node. Node 0 (the
// measurement, which the cost cannot move) keeps eq. 30 itself, as the paper writes it.
Eigen::Vector2d reachable_velocity(const SampcParams& params, const SampcInput& input,
                                   const Eigen::Vector3d& at, const Eigen::Vector2d& wanted,
                                   int k) {
  if (k == 0 || !(params.eq30_acceleration_limit_m_s2 > 0.0)) return wanted;
  const Eigen::Vector3d& omega = input.ugv.angular_velocity_rad_s;
  const Eigen::Vector3d p0 = input.uav_state.segment<3>(kPosition);
  const Eigen::Vector3d v0 = input.uav_state.segment<3>(kVelocity);
  const Eigen::Vector2d rotation_at = omega.cross(at).head<2>();
  const Eigen::Vector2d translation_relative_now = (v0 + omega.cross(p0)).head<2>();
  Eigen::Vector2d change = wanted + rotation_at - translation_relative_now;
  const double reachable = params.eq30_acceleration_limit_m_s2 * k * params.step_s;
  if (change.norm() > reachable) change *= reachable / change.norm();
  return translation_relative_now + change - rotation_at;
}

// xy-z-ref (eqs. 28-35): track height and the squared horizontal distance to the UGV's
// axis; the eq. 30 velocity reference; nose turning toward the UGV.
void build_transition_cost(const SampcParams& params, const SampcInput& input, double held_yaw_rad,
                           const YawTrack& previous_yaw, double elapsed_s,
                           const model::UavState* predicted_states, double intercept_lead_fraction,
                           HorizonCost& cost) {
  WeightSet w = params.transition_weights;
  if (params.mode == Mode::NoRefVxy) w.velocity.head<2>().setZero();

  const Eigen::Vector3d p = input.uav_state.segment<3>(kPosition);
  const double d0 = p.head<2>().squaredNorm();
  const double horizontal_distance = std::sqrt(d0);
  const bool direction_defined = horizontal_distance > params.yaw_hold_radius_m;
  const double target_yaw = direction_defined ? std::atan2(-p.y(), -p.x()) : held_yaw_rad;
  const YawPlan yaw = plan_yaw(params, input, target_yaw, previous_yaw, elapsed_s);
  const double reference_speed_xy = input.reference.velocity_m_s[0].head<2>().norm();
  const double distance_weight0 =
      w.distance_gain * std::exp(params.e2_per_m2 * d0) + w.distance_offset;
  // Intercept: where its prediction holds, the law on its own node count; otherwise exactly
  // cover (eq. 30), with the reason kept for the logs.
  if (params.mode == Mode::Intercept) {
    cost.intercept.fallback = prediction_fallback(params.intercept, input.ugv);
  }
  const bool intercepting =
      params.mode == Mode::Intercept && cost.intercept.fallback == InterceptFallback::None;
  const int velocity_nodes =
      intercepting ? params.intercept.velocity_nodes : params.custom_velocity_nodes;

  for (int k = 0; k <= params.horizon_steps; ++k) {
    NodeCost& node = cost.nodes[k];
    const double state_decay = std::exp(-params.e0 * k);
    node.position_ref_m = input.reference.position_m[k];
    node.position_weight = state_decay * w.position;
    // docs/model.md puts eq. 30 "at k = 0", but x0 is fixed to the measurement in multiple
    // shooting, so a cost there steers nothing. It is kept there (the paper's reading) and
    // also put on the first free nodes 1..custom_velocity_nodes, the first predicted states,
    // where it acts; later nodes weigh only the vertical velocity. Eq. 30 is a velocity at
    // a position, so a free node takes it at its own predicted position (the frame turns
    // and the UAV moves by then); v0d stays the plan's speed now, as in the paper.
    node.velocity_ref_m_s = Eigen::Vector3d(0.0, 0.0, input.reference.velocity_m_s[k].z());
    if (k <= velocity_nodes) {
      const Eigen::Vector3d at = k > 0 && predicted_states != nullptr
                                     ? Eigen::Vector3d(predicted_states[k].segment<3>(kPosition))
                                     : p;
      Eigen::Vector2d wanted =
          eq30_velocity(params, input.ugv.angular_velocity_rad_s, at, reference_speed_xy);
      if (intercepting) {
        const InterceptVelocity law = intercept_velocity(
            params.intercept, input.ugv, at, reference_speed_xy, wanted, input.speed_limit_m_s);
        wanted += intercept_lead_fraction * (law.velocity_m_s - wanted);
        if (k == 0) cost.intercept = law;
      }
      node.velocity_ref_m_s.head<2>() = reachable_velocity(params, input, at, wanted, k);
      node.velocity_weight = state_decay * w.velocity;
    } else {
      node.velocity_weight = Eigen::Vector3d(0.0, 0.0, state_decay * w.velocity.z());
    }
    node.attitude_ref = yaw_reference(params, yaw, k);
    node.attitude_weight = state_decay * w.attitude;
    node.squared_distance_ref_m2 = input.reference.position_m[k].head<2>().squaredNorm();
    node.squared_distance_weight = std::exp(-params.e1 * k) * distance_weight0;
    node.input_ref = model::hover_input();
    node.input_weight = std::exp(-params.e3 * k) * w.input;
  }
  cost.yaw_ref_rad = target_yaw;
  cost.yaw_track = yaw.track;
}

}  // namespace

void build_horizon_cost(const SampcParams& params, const SampcInput& input, double held_yaw_rad,
                        HorizonCost& cost, const YawTrack& previous_yaw, double elapsed_s,
                        const model::UavState* predicted_states, double intercept_lead_fraction) {
  cost.horizon_steps = params.horizon_steps;
  cost.intercept = InterceptVelocity{};
  cost.reference_mode = reference_mode_for(params.mode, input.stage);
  if (cost.reference_mode == ReferenceMode::XyzRef) {
    build_tracking_cost(params, input, previous_yaw, elapsed_s, cost);
  } else {
    build_transition_cost(params, input, held_yaw_rad, previous_yaw, elapsed_s, predicted_states,
                          intercept_lead_fraction, cost);
  }
  // Terminal node: scaled state weights, no input.
  NodeCost& terminal = cost.nodes[params.horizon_steps];
  terminal.position_weight *= params.terminal_weight_scale;
  terminal.velocity_weight *= params.terminal_weight_scale;
  terminal.attitude_weight *= params.terminal_weight_scale;
  terminal.squared_distance_weight *= params.terminal_weight_scale;
  terminal.input_weight.setZero();
  // The input-rate term is the caller's (Sampc knows the previous command): none by default.
  for (int k = 0; k <= params.horizon_steps; ++k) cost.nodes[k].input_rate_weight.setZero();
}

}  // namespace cover::sampc
