#pragma once

#include <optional>
#include <string_view>

#include <Eigen/Core>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/sampc/intercept_velocity.hpp"
#include "cover/vocabulary/method.hpp"
#include "cover/vocabulary/state.hpp"

namespace cover::sampc {

// Longest horizon the fixed-size workspaces hold; `horizon_steps` may be anything up to it.
inline constexpr int kMaxHorizon = 40;

// Whether the transition stage's planned start velocity drops the frame-rotation part
// (eq. 23, v0 = v + Omega x p): COVER and its ablation do, the CoNi-MPC baseline does not.
// For the mission layer, which plans the stage references.
inline bool compensates_frame_rotation(Mode mode) {
  return mode != Mode::ConiMpc;
}

// The weight set of one reference mode (Table 2): index 0 is the transition stage's
// xy-z-ref set, index 1 the x-y-z-ref set of the initial and final stages.
struct WeightSet {
  Eigen::Vector3d position;      // Qp  [x, y, z]
  Eigen::Vector3d velocity;      // Qv  [x, y, z]
  Eigen::Vector4d attitude;      // Qq  [w, x, y, z]
  Eigen::Vector4d input;         // R   [F, wx, wy, wz], must be > 0
  double distance_gain = 0.0;    // q0 of Qd (xy-z-ref only), 1/m^4
  double distance_offset = 0.0;  // q1 of Qd (xy-z-ref only), 1/m^4

  // The x-y-z-ref set (tracking_weights) is declared without the distance terms.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("position", self.position, Field("", "Qp [x, y, z]").at_least(0.0));
    visit("velocity", self.velocity, Field("", "Qv [x, y, z]").at_least(0.0));
    visit("attitude", self.attitude, Field("", "Qq [w, x, y, z]").at_least(0.0));
    // R > 0 keeps every QP strictly convex in the inputs (the Riccati recursion needs it).
    visit("input", self.input, Field("", "R [F, wx, wy, wz]").above(0.0));
    visit("distance_gain", self.distance_gain, Field("1/m^4", "q0 of Qd").at_least(0.0));
    visit("distance_offset", self.distance_offset, Field("1/m^4", "q1 of Qd").at_least(0.0));
  }
};

// Parameters of SAMPC (paper sec. 4.3, eqs. 24-35). Defaults are those shipped in
// config/sampc.yaml, where each choice the paper leaves open is explained.
struct SampcParams {
  Mode mode = Mode::Cover;

  int horizon_steps = 20;          // N
  double step_s = 0.1;             // dt of one shooting interval
  double control_period_s = 0.01;  // how far the warm start is shifted between calls (100 Hz)

  // Exponential decays over the horizon: Q by exp(-e0 k), Qd by exp(-e1 k), R by exp(-e3 k);
  // Qd grows as the current squared distance d0 shrinks through exp(e2 d0), e2 < 0.
  double e0 = 0.05;
  double e1 = 0.05;
  double e2_per_m2 = -0.5;
  double e3 = 0.02;

  double thrust_min_m_s2 = 2.0;
  double thrust_max_m_s2 = 20.0;
  double roll_pitch_rate_max_rad_s = 3.14;
  double yaw_rate_max_rad_s = 1.5;

  // Table 2's, except the vertical velocity weight Q0v_z: 300 against the paper's 100. At
  // the frame switch the UAV tilts hard toward the new UGV, and with 100 its height gave way
  // (a 0.3 m/s sink and the thrust's dip and surge, Fig. 8's largest thrust steps).
  WeightSet transition_weights{Eigen::Vector3d(0, 0, 200),
                               Eigen::Vector3d(350, 350, 300),
                               Eigen::Vector4d::Constant(40),
                               Eigen::Vector4d(1, 30, 30, 5),
                               200.0,
                               100.0};
  WeightSet tracking_weights{Eigen::Vector3d(200, 200, 300),
                             Eigen::Vector3d(100, 100, 300),
                             Eigen::Vector4d::Constant(50),
                             Eigen::Vector4d(1, 20, 20, 5),
                             0.0,
                             0.0};
  // x-y-z-ref: node k's thrust and attitude references are those that fly the plan's
  // acceleration there (the model solved for R(q) [0, 0, F] at the reference's position,
  // velocity and acceleration, yaw from the yaw reference), its body-rate references those
  // that turn node k's attitude reference into node k + 1's; false: hover thrust, level,
  // zero rates (Table 2's around-hover references). Never at coni-mpc's transition stage.
  bool tracking_feed_forward = true;
  // The terminal node k = N uses the stage weights of k = N times this factor.
  double terminal_weight_scale = 2.0;

  // Below this horizontal distance to the UGV the nose-at-UGV yaw is ill-defined: the last
  // yaw reference is held, and the eq. 30 direction term is dropped.
  double yaw_hold_radius_m = 0.2;
  // The yaw reference over the horizon starts at the UAV's measured yaw and turns toward the
  // stage's target yaw (nose at the UGV, or the UGV's x axis) at most this fast: a frame
  // switch can put the target 180 deg away, and a step reference there gives a thrust and
  // body-rate spike (and an attitude error whose sign can flip). Must be <= yaw_rate_max_rad_s.
  double yaw_reference_rate_rad_s = 0.8;
  // The yaw reference's start stays within this of the measured yaw (rad): when the UAV
  // cannot keep up (a frame turning faster than the yaw rate bound) the error stays bounded.
  double yaw_reference_max_lag_rad = 0.6;
  // A turn in progress keeps its direction until the other way round is shorter by more
  // than this (rad): the error drifting through 180 deg must not reverse the yaw plan.
  double yaw_flip_hysteresis_rad = 0.8;
  // Eq. 30's customised velocity reference sits on the first `custom_velocity_nodes` free
  // nodes k = 1..n (x0 is fixed to the measurement in multiple shooting, so at k = 0 it
  // would cost nothing and steer nothing), each at its own predicted position. Must be in
  // [1, horizon_steps].
  int custom_velocity_nodes = 10;
  // Node k's eq. 30 reference is at most this * k * step_s (m/s) from the UAV's velocity
  // relative to the UGV's translation now: eq. 30 asks for its velocity at once, which after
  // a frame switch is an attitude step. 0 disables the limit.
  double eq30_acceleration_limit_m_s2 = 2.0;
  // Frame switch (Sampc::reset_frame()): for `switch_smoothing_s` after it, node 0 also pays
  // switch_input_rate_weight * (u0 - previous command)^2, the weight ramping linearly from
  // full to 0. The new stage's optimum can differ sharply from the old plan (e.g. a pitch
  // step of -1.3 rad/s on the circle); this lets the command walk there over a few steps
  // instead of jumping. Order [F, wx, wy, wz], each >= 0; 0 s disables it. Over the same
  // time the intercept law's lead builds up from 0 (build_horizon_cost's
  // intercept_lead_fraction).
  double switch_smoothing_s = 0.5;
  Eigen::Vector4d switch_input_rate_weight{30.0, 1000.0, 1000.0, 300.0};
  // Node 0's input-rate weight throughout an xy-z-ref transition (cover, no-ref-vxy,
  // intercept), order [F, wx, wy, wz], each >= 0 (the larger of this and the switch's
  // ramp). The transition weighs the velocity error at 350 against the tracking stages'
  // 100, so the relative velocity's measurement noise reached the body rates 3.5x amplified;
  // a twentieth of the switch's weight filters it (docs/benchmarks.md: circle switch peaks
  // 0.207 / 0.375 -> 0.161 / 0.271, paths within 0.002). 0 disables it.
  Eigen::Vector4d transition_input_rate_weight{1.5, 50.0, 50.0, 15.0};

  // Solver: 1 SQP iteration per call is the real-time iteration. After reset() (no warm
  // start) `cold_start_iterations` are spent instead. `max_sqp_iterations` > 1 iterates
  // until the largest step component is below `sqp_step_tolerance`.
  int max_sqp_iterations = 1;
  int cold_start_iterations = 5;
  // After a frame switch (reset_frame()) the previous inputs are a good guess and one
  // iteration per control period moves the command toward the new stage's optimum over a
  // few periods; converging at once steps the body rates (1.1 rad/s in one period on the
  // circle with 5 iterations, 0.6 with 1).
  int frame_switch_iterations = 1;
  double sqp_step_tolerance = 1e-6;
  int max_qp_iterations = 25;  // active-set changes per QP

  // The intercept method's law and when it falls back to eq. 30 (mode intercept only).
  InterceptParams intercept;

  // Input sanity: beyond these the solve is refused with status invalid_input.
  double max_abs_position_m = 1000.0;
  double max_abs_speed_m_s = 50.0;
  double max_abs_angular_rate_rad_s = 20.0;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list. Bounds against other fields are in validate().
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("mode", self.mode, Field("", "reference mode (the method)").one_of(kModes));
    visit("horizon_steps", self.horizon_steps,
          Field("", "N, shooting intervals").at_least(1.0).at_most(kMaxHorizon));
    visit("step_s", self.step_s, Field("s", "dt of one shooting interval").above(0.0));
    visit("control_period_s", self.control_period_s,
          Field("s", "warm-start shift between calls; = mission.control_period_s").above(0.0));
    visit("e0", self.e0, Field("", "Q decays by exp(-e0 k)").at_least(0.0));
    visit("e1", self.e1, Field("", "Qd decays by exp(-e1 k)").at_least(0.0));
    visit("e3", self.e3, Field("", "R decays by exp(-e3 k)").at_least(0.0));
    visit("e2_per_m2", self.e2_per_m2,
          Field("1/m^2", "Qd grows by exp(e2 d0) as the squared distance d0 shrinks")
              .at_most(0.0)
              .hint("Qd grows as the UAV nears the UGV"));
    // The thrust bounds bracket hover (g).
    visit("thrust_min_m_s2", self.thrust_min_m_s2,
          Field("m/s^2", "lowest collective thrust, below hover (g)")
              .above(0.0)
              .below(model::kGravity_m_s2));
    visit("thrust_max_m_s2", self.thrust_max_m_s2,
          Field("m/s^2", "highest collective thrust, above hover (g)").above(model::kGravity_m_s2));
    visit("roll_pitch_rate_max_rad_s", self.roll_pitch_rate_max_rad_s,
          Field("rad/s", "|wx|, |wy| bound").above(0.0));
    visit("yaw_rate_max_rad_s", self.yaw_rate_max_rad_s, Field("rad/s", "|wz| bound").above(0.0));
    visit("transition_weights", self.transition_weights,
          Field("", "xy-z-ref weight set (transition stage)"));
    visit("tracking_weights", self.tracking_weights,
          Field("", "x-y-z-ref weight set (initial and final stages)")
              .without({"distance_gain", "distance_offset"}));
    visit("tracking_feed_forward", self.tracking_feed_forward,
          Field("", "x-y-z-ref thrust, attitude and rate references fly the plan"));
    visit("terminal_weight_scale", self.terminal_weight_scale,
          Field("", "node N's weights are node N's stage weights times this").above(0.0));
    visit("yaw_hold_radius_m", self.yaw_hold_radius_m,
          Field("m", "closer to the UGV the yaw reference is held").at_least(0.0));
    visit("yaw_reference_rate_rad_s", self.yaw_reference_rate_rad_s,
          Field("rad/s", "the yaw reference turns at most this fast; <= yaw_rate_max_rad_s")
              .above(0.0));
    visit("yaw_reference_max_lag_rad", self.yaw_reference_max_lag_rad,
          Field("rad", "the yaw reference's start stays this close to the measured yaw")
              .above(0.0)
              .below(1.5));
    visit("yaw_flip_hysteresis_rad", self.yaw_flip_hysteresis_rad,
          Field("rad", "a yaw turn reverses only when the other way is this much shorter")
              .at_least(0.0)
              .below(3.14));
    visit("custom_velocity_nodes", self.custom_velocity_nodes,
          Field("", "free nodes 1..n carrying eq. 30; <= horizon_steps").at_least(1.0));
    visit("eq30_acceleration_limit_m_s2", self.eq30_acceleration_limit_m_s2,
          Field("m/s^2", "node k's eq. 30 reference within this * k * step_s of the velocity")
              .at_least(0.0)
              .hint("0 disables"));
    visit("switch_smoothing_s", self.switch_smoothing_s,
          Field("s", "input-rate cost ramp after a frame switch")
              .at_least(0.0)
              .at_most(10.0)
              .hint("0 disables"));
    visit("switch_input_rate_weight", self.switch_input_rate_weight,
          Field("", "node 0's input-rate weight after a switch [F, wx, wy, wz]").at_least(0.0));
    visit("transition_input_rate_weight", self.transition_input_rate_weight,
          Field("", "node 0's input-rate weight in a transition [F, wx, wy, wz]")
              .at_least(0.0)
              .hint("0 disables"));
    visit("max_sqp_iterations", self.max_sqp_iterations,
          Field("", "SQP iterations per call").at_least(1.0));
    visit("cold_start_iterations", self.cold_start_iterations,
          Field("", "SQP iterations after reset()").at_least(1.0));
    visit("frame_switch_iterations", self.frame_switch_iterations,
          Field("", "SQP iterations after reset_frame()").at_least(1.0));
    visit("sqp_step_tolerance", self.sqp_step_tolerance,
          Field("", "stop iterating below this largest step component").above(0.0));
    visit("max_qp_iterations", self.max_qp_iterations,
          Field("", "active-set changes per QP").at_least(1.0));
    visit("intercept", self.intercept, Field("", "the intercept method's law (mode intercept)"));
    visit("max_abs_position_m", self.max_abs_position_m,
          Field("m", "input sanity: |position| beyond is invalid_input").above(0.0));
    visit("max_abs_speed_m_s", self.max_abs_speed_m_s,
          Field("m/s", "input sanity: |velocity| beyond is invalid_input").above(0.0));
    visit("max_abs_angular_rate_rad_s", self.max_abs_angular_rate_rad_s,
          Field("rad/s", "input sanity: |rate| beyond is invalid_input").above(0.0));
  }

  Eigen::Vector4d input_lower_bound() const;
  Eigen::Vector4d input_upper_bound() const;

  static SampcParams load(config::YamlReader& reader);
  // Reads the `sampc` section of a YAML file; throws config::ConfigError naming the key.
  static SampcParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static SampcParams from_yaml(const YAML::Node& document, const std::string& source);
  // Throws config::ConfigError naming the offending key.
  void validate() const;
};

}  // namespace cover::sampc
