#include "cover/sampc/horizon_cost.hpp"

#include <cmath>

#include "cover/model/quaternion.hpp"

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

  return position_weight.dot(position_error.cwiseAbs2()) +
         velocity_weight.dot(velocity_error.cwiseAbs2()) +
         attitude_weight.dot(attitude_error.cwiseAbs2()) +
         squared_distance_weight * distance_error * distance_error +
         input_weight.dot(input_error.cwiseAbs2());
}

namespace {

// x-y-z-ref (eqs. 25-27 with the initial/final weights): follow the plan in full, nose
// along the UGV's x axis.
void build_tracking_cost(const SampcParams& params, const SampcInput& input, HorizonCost& cost) {
  const WeightSet& w = params.tracking_weights;
  for (int k = 0; k <= params.horizon_steps; ++k) {
    NodeCost& node = cost.nodes[k];
    const double state_decay = std::exp(-params.e0 * k);
    node.position_ref_m = input.reference.position_m[k];
    node.position_weight = state_decay * w.position;
    node.velocity_ref_m_s = input.reference.velocity_m_s[k];
    node.velocity_weight = state_decay * w.velocity;
    node.attitude_ref = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
    node.attitude_weight = state_decay * w.attitude;
    node.squared_distance_ref_m2 = 0.0;
    node.squared_distance_weight = 0.0;
    node.input_ref = model::hover_input();
    node.input_weight = std::exp(-params.e3 * k) * w.input;
  }
  cost.yaw_ref_rad = 0.0;
}

// xy-z-ref (eqs. 28-35): track height and the squared horizontal distance to the UGV's
// axis; the velocity reference of eq. 30 at k = 0 only; nose at the UGV.
void build_transition_cost(const SampcParams& params, const SampcInput& input, double held_yaw_rad,
                           HorizonCost& cost) {
  WeightSet w = params.transition_weights;
  if (params.mode == Mode::NoRefVxy) w.velocity.head<2>().setZero();

  const Eigen::Vector3d p = input.uav_state.segment<3>(kPosition);
  const double d0 = p.head<2>().squaredNorm();
  const double horizontal_distance = std::sqrt(d0);
  const bool direction_defined = horizontal_distance > params.yaw_hold_radius_m;
  const double yaw = direction_defined ? std::atan2(-p.y(), -p.x()) : held_yaw_rad;
  const double reference_speed_xy = input.reference.velocity_m_s[0].head<2>().norm();
  const double distance_weight0 =
      w.distance_gain * std::exp(params.e2_per_m2 * d0) + w.distance_offset;

  // Eq. 30: cancel the frame-rotation-induced motion and head at the UGV at the plan's speed.
  Eigen::Vector3d velocity_ref0 = -input.ugv.angular_velocity_rad_s.cross(p);
  if (direction_defined) {
    velocity_ref0.head<2>() -= p.head<2>() / horizontal_distance * reference_speed_xy;
  }
  velocity_ref0.z() = input.reference.velocity_m_s[0].z();

  for (int k = 0; k <= params.horizon_steps; ++k) {
    NodeCost& node = cost.nodes[k];
    const double state_decay = std::exp(-params.e0 * k);
    node.position_ref_m = input.reference.position_m[k];
    node.position_weight = state_decay * w.position;
    if (k == 0) {
      node.velocity_ref_m_s = velocity_ref0;
      node.velocity_weight = state_decay * w.velocity;
    } else {
      node.velocity_ref_m_s = Eigen::Vector3d(0.0, 0.0, input.reference.velocity_m_s[k].z());
      node.velocity_weight = Eigen::Vector3d(0.0, 0.0, state_decay * w.velocity.z());
    }
    node.attitude_ref = model::yaw_quaternion(yaw);
    node.attitude_weight = state_decay * w.attitude;
    node.squared_distance_ref_m2 = input.reference.position_m[k].head<2>().squaredNorm();
    node.squared_distance_weight = std::exp(-params.e1 * k) * distance_weight0;
    node.input_ref = model::hover_input();
    node.input_weight = std::exp(-params.e3 * k) * w.input;
  }
  cost.yaw_ref_rad = yaw;
}

}  // namespace

void build_horizon_cost(const SampcParams& params, const SampcInput& input, double held_yaw_rad,
                        HorizonCost& cost) {
  cost.horizon_steps = params.horizon_steps;
  cost.reference_mode = reference_mode_for(params.mode, input.stage);
  if (cost.reference_mode == ReferenceMode::XyzRef) {
    build_tracking_cost(params, input, cost);
  } else {
    build_transition_cost(params, input, held_yaw_rad, cost);
  }
  // Terminal node: scaled state weights, no input.
  NodeCost& terminal = cost.nodes[params.horizon_steps];
  terminal.position_weight *= params.terminal_weight_scale;
  terminal.velocity_weight *= params.terminal_weight_scale;
  terminal.attitude_weight *= params.terminal_weight_scale;
  terminal.squared_distance_weight *= params.terminal_weight_scale;
  terminal.input_weight.setZero();
}

}  // namespace cover::sampc
