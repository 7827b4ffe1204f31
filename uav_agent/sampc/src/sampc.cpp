#include "cover/sampc/sampc.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cover/model/dynamics.hpp"
#include "cover/sampc/qp_riccati.hpp"

namespace cover::sampc {

using model::idx::kPosition;
using model::idx::kQuaternion;
using model::idx::kVelocity;

namespace {

using Clock = std::chrono::steady_clock;

double elapsed_us(Clock::time_point since) {
  return std::chrono::duration<double, std::micro>(Clock::now() - since).count();
}

// A UGV accelerometer beyond 10 g is not a ground vehicle: treat it as a corrupt message.
constexpr double kMaxSpecificForce_m_s2 = 100.0;

// Returns nullptr when `input` is usable, else why it is not.
const char* check_input(const SampcParams& params, const SampcInput& input) {
  const model::UavState& x = input.uav_state;
  if (!x.allFinite()) return "non-finite UAV state";
  if (x.segment<3>(kPosition).cwiseAbs().maxCoeff() > params.max_abs_position_m) {
    return "UAV position beyond max_abs_position_m";
  }
  if (x.segment<3>(kVelocity).norm() > params.max_abs_speed_m_s) {
    return "UAV speed beyond max_abs_speed_m_s";
  }
  const double q_norm = x.segment<4>(kQuaternion).norm();
  if (q_norm < 0.5 || q_norm > 1.5) return "UAV attitude quaternion far from unit norm";
  if (!input.ugv.all_finite()) return "non-finite UGV motion";
  if (input.ugv.angular_velocity_rad_s.norm() > params.max_abs_angular_rate_rad_s ||
      input.ugv.angular_acceleration_rad_s2.norm() > params.max_abs_angular_rate_rad_s) {
    return "UGV angular rate or acceleration beyond max_abs_angular_rate_rad_s";
  }
  if (input.ugv.specific_force_m_s2.norm() > kMaxSpecificForce_m_s2) {
    return "UGV specific force beyond 10 g";
  }
  for (int k = 0; k <= params.horizon_steps; ++k) {
    const Eigen::Vector3d& p = input.reference.position_m[k];
    const Eigen::Vector3d& v = input.reference.velocity_m_s[k];
    if (!p.allFinite() || !v.allFinite()) return "non-finite reference";
    if (p.cwiseAbs().maxCoeff() > params.max_abs_position_m ||
        v.norm() > params.max_abs_speed_m_s) {
      return "reference beyond the position/speed sanity bounds";
    }
  }
  return nullptr;
}

model::UavState normalised(model::UavState x) {
  x.segment<4>(kQuaternion).normalize();
  return x;
}

}  // namespace

struct Sampc::Workspace {
  SampcParams params;
  model::Input lower, upper;

  // The current plan (multiple shooting nodes) and the UGV motion at each node.
  std::array<model::UavState, kMaxHorizon + 1> x;
  std::array<model::Input, kMaxHorizon> u;
  std::array<model::UgvMotion, kMaxHorizon + 1> ugv;
  HorizonCost cost;
  RiccatiQp qp;
  double cost_value = 0.0;
  double last_step = 0.0;  // largest |dx|, |du| component of the last SQP step

  bool has_guess = false;      // false until the first solve and after reset()
  bool reroll_states = false;  // reset_frame(): keep u, roll x out from the new measurement
  // The last command handed out, and how long node 0 still pays for moving away from it.
  model::Input last_command = model::hover_input();
  double smoothing_left_s = 0.0;
  bool prepared = false;     // a factorisation waits for its feedback
  bool needs_shift = false;  // a feedback happened since the last preparation
  model::Stage prepared_stage = model::Stage::Initial;
  double held_yaw_rad = 0.0;
  // The yaw reference's start at the previous control step (see YawTrack); repeated
  // preparations within one step (SQP iterations) all start from the same one.
  YawTrack previous_yaw_track;
  double prepare_us = 0.0;

  int N() const { return params.horizon_steps; }

  // The measurement with its quaternion on the plan's side: q and -q are the same attitude,
  // and a sensor may hand over either (its sign flips e.g. as the yaw passes 180 deg). Taken
  // as is, a flipped sign is a state jump of |2q| = 2 against the warm start, and the one
  // RTI step that absorbs it commanded full thrust.
  model::UavState measured_state(const SampcInput& input) const {
    model::UavState x0 = normalised(input.uav_state);
    if (has_guess && x0.segment<4>(kQuaternion).dot(x[0].segment<4>(kQuaternion)) < 0.0) {
      x0.segment<4>(kQuaternion) *= -1.0;
    }
    return x0;
  }

  void initialise_guess(const model::UavState& x0) {
    x[0] = x0;
    for (int k = 0; k < N(); ++k) {
      u[k] = model::hover_input();
      x[k + 1] = model::uav_rk4_step(x[k], u[k], ugv[k], params.step_s);
    }
    has_guess = true;
  }

  // Moves the plan forward by one control period: whole nodes, then linear interpolation
  // between neighbours for the fraction of a node (the loop runs 10x faster than dt).
  void shift_guess() {
    double remaining = params.control_period_s / params.step_s;
    while (remaining > 1e-12) {
      const double f = std::min(remaining, 1.0);
      const model::UavState extension =
          model::uav_rk4_step(x[N()], u[N() - 1], ugv[N()], params.step_s);
      for (int k = 0; k < N(); ++k) x[k] = normalised((1 - f) * x[k] + f * x[k + 1]);
      x[N()] = normalised((1 - f) * x[N()] + f * extension);
      for (int k = 0; k + 1 < N(); ++k) u[k] = (1 - f) * u[k] + f * u[k + 1];
      remaining -= f;
    }
  }

  // The intercept law's lead builds up over the switch smoothing (0 at the switch, whole
  // after switch_smoothing_s): at the switch the UAV still flies the old frame's velocity,
  // and the whole lead at once asked for a tilt on top of the approach's (the star's thrust
  // peak 0.416 against coni-mpc's 0.365 m/s^2; ramped 0.362, docs/benchmarks.md).
  double intercept_lead_fraction() const { return 1.0 - switch_smoothing_left_fraction(); }

  // What is left of the switch smoothing: 1 at the frame switch, 0 once it is over (or off).
  double switch_smoothing_left_fraction() const {
    if (!(smoothing_left_s > 0.0) || !(params.switch_smoothing_s > 0.0)) return 0.0;
    return std::min(1.0, smoothing_left_s / params.switch_smoothing_s);
  }

  // The command leaves the solver: the next control step's input-rate term is anchored here.
  SampcOutput hand_out(const SampcOutput& out) {
    if (!is_error(out.status)) last_command = out.command;
    return out;
  }

  // Node 0's input-rate weight: after a frame switch (SampcParams::switch_smoothing_s), and
  // at an xy-z-ref transition (SampcParams::transition_input_rate_weight), the larger.
  model::Input input_rate_weight() const {
    model::Input weight = switch_smoothing_left_fraction() * params.switch_input_rate_weight;
    if (cost.reference_mode == ReferenceMode::XyZRef) {
      weight = weight.cwiseMax(params.transition_input_rate_weight);
    }
    return weight;
  }

  // Gauss-Newton model of the cost and linearised dynamics at the current plan.
  void linearise() {
    cost_value = 0.0;
    for (int k = 0; k <= N(); ++k) {
      QpNode& node = qp.nodes[k];
      const NodeCost& c = cost.nodes[k];
      const bool terminal = k == N();
      const model::Input uk = terminal ? model::hover_input() : u[k];
      model::UavState grad_x = model::UavState::Zero();
      model::Input grad_u = model::Input::Zero();
      cost_value += c.evaluate(x[k], uk, &grad_x, &grad_u);
      node.q = grad_x;
      // H = 2 J' W J: diagonal for p, v, a projector for q, plus the rank-one d-term.
      node.Q.setZero();
      node.Q.diagonal().segment<3>(kPosition) = 2.0 * c.position_weight;
      node.Q.diagonal().segment<3>(kVelocity) = 2.0 * c.velocity_weight;
      const Eigen::Matrix4d attitude_jacobian = c.attitude_error_jacobian();
      node.Q.block<4, 4>(kQuaternion, kQuaternion).noalias() =
          2.0 * attitude_jacobian * c.attitude_weight.asDiagonal() * attitude_jacobian;
      const Eigen::Vector2d d_jacobian = 2.0 * x[k].segment<2>(kPosition);
      node.Q.block<2, 2>(kPosition, kPosition) +=
          2.0 * c.squared_distance_weight * d_jacobian * d_jacobian.transpose();
      // The d-term's own curvature 2 wd (d - d_ref) * 2 I where it is convex (UAV outside
      // the reference radius): plain Gauss-Newton ignores it and then overshoots back and
      // forth across the radius; where it is concave it is left out to keep the QP convex.
      const double distance_residual =
          x[k].segment<2>(kPosition).squaredNorm() - c.squared_distance_ref_m2;
      if (distance_residual > 0.0) {
        node.Q.block<2, 2>(kPosition, kPosition).diagonal().array() +=
            4.0 * c.squared_distance_weight * distance_residual;
      }
      if (terminal) break;
      node.r = grad_u;
      node.R = (2.0 * (c.input_weight + c.input_rate_weight)).asDiagonal();
      node.S.setZero();
      node.lower = lower - u[k];
      node.upper = upper - u[k];
      const model::UavState next =
          model::uav_rk4_step(x[k], u[k], ugv[k], params.step_s, node.A, node.B);
      node.c = next - x[k + 1];
    }
  }

  void prepare(const SampcInput& input, bool shift) {
    const auto start = Clock::now();
    prepared = false;
    if (check_input(params, input) != nullptr) return;  // feedback reports it
    for (int k = 0; k <= N(); ++k) ugv[k] = input.ugv.advanced(k * params.step_s);
    const model::UavState x0 = measured_state(input);
    if (!has_guess) {
      initialise_guess(x0);
      previous_yaw_track = YawTrack{};
    } else if (shift && needs_shift) {
      shift_guess();
      previous_yaw_track = cost.yaw_track;
      smoothing_left_s = std::max(0.0, smoothing_left_s - params.control_period_s);
    }
    needs_shift = false;
    x[0] = x0;
    if (reroll_states) {
      // The old frame's states mean nothing here (and its yaw track neither); its inputs do.
      for (int k = 0; k < N(); ++k) {
        x[k + 1] = model::uav_rk4_step(x[k], u[k], ugv[k], params.step_s);
      }
      previous_yaw_track = YawTrack{};
      smoothing_left_s = params.switch_smoothing_s;
      reroll_states = false;
    }
    build_horizon_cost(params, input, held_yaw_rad, cost, previous_yaw_track,
                       params.control_period_s, x.data(), intercept_lead_fraction());
    // The anchor is the command handed out at the last control step, not the previous SQP
    // iterate: anchored at the iterate, solve()'s iterations (cold start, tests) were a
    // proximal-point method on u0 whose converged plan no longer paid for leaving the last
    // command at all. In HorizonCost, so the reference solver sees the term too.
    cost.nodes[0].input_rate_weight = input_rate_weight();
    cost.nodes[0].previous_input = last_command;
    linearise();
    qp.prepare(N());
    prepared = true;
    prepared_stage = input.stage;
    prepare_us = elapsed_us(start);
  }

  bool plan_finite() const {
    for (int k = 0; k < N(); ++k) {
      if (!x[k].allFinite() || !u[k].allFinite()) return false;
    }
    return x[N()].allFinite();
  }

  void reset() {
    has_guess = false;
    reroll_states = false;
    smoothing_left_s = 0.0;
    prepared = false;
    needs_shift = false;
    held_yaw_rad = 0.0;
    previous_yaw_track = YawTrack{};
  }

  SampcOutput hover(SolveStatus status, const char* reason) {
    reset();
    // Leave no NaN behind for planned_input(); the next call re-initialises anyway.
    for (int k = 0; k < N(); ++k) u[k] = model::hover_input();
    SampcOutput out;
    out.command = model::hover_input();
    out.status = status;
    out.reason = reason;
    return out;
  }

  // One QP on the prepared linearisation and the full step on the plan.
  SampcOutput feedback(const SampcInput& input) {
    const auto start = Clock::now();
    if (const char* reason = check_input(params, input)) {
      SampcOutput out = hover(SolveStatus::InvalidInput, reason);
      out.feedback_us = elapsed_us(start);
      return out;
    }
    if (!prepared || prepared_stage != input.stage) prepare(input, true);

    const model::UavState x0 = measured_state(input);
    const QpResult qp_result = qp.solve_prepared(x0 - x[0], params.max_qp_iterations);
    last_step = 0.0;
    for (int k = 0; k <= N(); ++k) {
      last_step = std::max(last_step, qp.dx(k).cwiseAbs().maxCoeff());
      x[k] = normalised(x[k] + qp.dx(k));
      if (k == N()) break;
      last_step = std::max(last_step, qp.du(k).cwiseAbs().maxCoeff());
      // The box holds exactly at a converged QP; the clamp only guards an unfinished one.
      u[k] = (u[k] + qp.du(k)).cwiseMax(lower).cwiseMin(upper);
    }
    prepared = false;
    needs_shift = true;
    held_yaw_rad = cost.yaw_ref_rad;

    if (!plan_finite() || !std::isfinite(cost_value)) {
      SampcOutput out = hover(SolveStatus::NonFiniteSolution, "solver produced NaN/Inf");
      out.feedback_us = elapsed_us(start);
      return out;
    }
    SampcOutput out;
    out.command = u[0];
    out.status = qp_result.converged ? SolveStatus::Ok : SolveStatus::QpNotConverged;
    out.reason = qp_result.converged ? "" : "active-set QP hit max_qp_iterations";
    out.iterations = 1;
    out.qp_iterations = qp_result.iterations;
    out.cost = cost_value;
    out.prepare_us = prepare_us;
    out.feedback_us = elapsed_us(start);
    return out;
  }
};

Sampc::Sampc(const SampcParams& params) : ws_(std::make_unique<Workspace>()) {
  params.validate();
  ws_->params = params;
  ws_->lower = params.input_lower_bound();
  ws_->upper = params.input_upper_bound();
}

Sampc::~Sampc() = default;
Sampc::Sampc(Sampc&&) noexcept = default;
Sampc& Sampc::operator=(Sampc&&) noexcept = default;

void Sampc::prepare(const SampcInput& predicted_input) {
  ws_->prepare(predicted_input, true);
}

SampcOutput Sampc::feedback(const SampcInput& input) {
  return ws_->hand_out(ws_->feedback(input));
}

SampcOutput Sampc::solve(const SampcInput& input) {
  Workspace& ws = *ws_;
  int max_iterations = ws.params.max_sqp_iterations;
  if (!ws.has_guess) {
    max_iterations = std::max(ws.params.cold_start_iterations, max_iterations);
  } else if (ws.reroll_states) {
    max_iterations = std::max(ws.params.frame_switch_iterations, max_iterations);
  }
  ws.prepare(input, true);
  SampcOutput out = ws.feedback(input);
  double prepare_total = out.prepare_us;
  double feedback_total = out.feedback_us;
  bool converged = ws.last_step < ws.params.sqp_step_tolerance;
  while (!is_error(out.status) && !converged && out.iterations < max_iterations) {
    ws.prepare(input, false);  // re-linearise at the improved plan, same time instant
    const SampcOutput next = ws.feedback(input);
    const int iterations = out.iterations + 1;
    const int qp_iterations = out.qp_iterations + next.qp_iterations;
    out = next;
    out.iterations = iterations;
    out.qp_iterations = qp_iterations;
    prepare_total += next.prepare_us;
    feedback_total += next.feedback_us;
    converged = ws.last_step < ws.params.sqp_step_tolerance;
  }
  out.prepare_us = prepare_total;
  out.feedback_us = feedback_total;
  if (out.status == SolveStatus::Ok && ws.params.max_sqp_iterations > 1 && !converged) {
    out.status = SolveStatus::SqpNotConverged;
    out.reason = "SQP hit max_sqp_iterations before sqp_step_tolerance";
  }
  return ws.hand_out(out);
}

void Sampc::reset() {
  ws_->reset();
}

void Sampc::reset_frame() {
  Workspace& ws = *ws_;
  if (!ws.has_guess) return;  // nothing to carry over: the next call starts from hover
  ws.prepared = false;
  ws.reroll_states = true;
  ws.held_yaw_rad = 0.0;
}

void Sampc::set_mode(Mode mode) {
  Workspace& ws = *ws_;
  if (ws.params.mode == mode) return;
  ws.params.mode = mode;
  ws.prepared = false;  // the waiting factorisation was built with the other method's cost
}

bool Sampc::prepared() const {
  return ws_->prepared;
}

void Sampc::rehearse_feedback() {
  if (!ws_->prepared) return;
  ws_->qp.solve_prepared(VectorX::Zero(), ws_->params.max_qp_iterations);
}

model::UavState Sampc::predicted_state(double dt_s) const {
  const Workspace& ws = *ws_;
  return normalised(model::uav_rk4_step(ws.x[0], ws.last_command, ws.ugv[0], dt_s));
}

const SampcParams& Sampc::params() const {
  return ws_->params;
}

const HorizonCost& Sampc::horizon_cost() const {
  return ws_->cost;
}

model::UavState Sampc::planned_state(int k) const {
  return ws_->x[std::clamp(k, 0, ws_->N())];
}

model::Input Sampc::planned_input(int k) const {
  return ws_->u[std::clamp(k, 0, ws_->N() - 1)];
}

}  // namespace cover::sampc
