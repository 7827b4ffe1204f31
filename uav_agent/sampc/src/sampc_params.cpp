#include "cover/sampc/sampc_params.hpp"

#include <cmath>

#include "cover/model/state.hpp"

namespace cover::sampc {
namespace {

Mode parse_mode_or_throw(const std::string& text, const std::string& context) {
  if (const auto mode = parse_mode(text)) return *mode;
  throw config::ConfigError(context + ".mode: '" + text + "' is not one of " + mode_names(", "));
}

void load_weights(config::YamlReader reader, WeightSet& set, bool with_distance) {
  reader.optional("position", set.position);
  reader.optional("velocity", set.velocity);
  reader.optional("attitude", set.attitude);
  reader.optional("input", set.input);
  if (with_distance) {
    reader.optional("distance_gain", set.distance_gain);
    reader.optional("distance_offset", set.distance_offset);
  }
  reader.reject_unknown_keys();
}

void validate_weights(const WeightSet& set, const std::string& context) {
  config::check(set.position.allFinite() && (set.position.array() >= 0).all(),
                context + ".position", "weights must be finite and >= 0");
  config::check(set.velocity.allFinite() && (set.velocity.array() >= 0).all(),
                context + ".velocity", "weights must be finite and >= 0");
  config::check(set.attitude.allFinite() && (set.attitude.array() >= 0).all(),
                context + ".attitude", "weights must be finite and >= 0");
  // R > 0 keeps every QP strictly convex in the inputs (the Riccati recursion needs it).
  config::check(set.input.allFinite() && (set.input.array() > 0).all(), context + ".input",
                "weights must be finite and > 0");
  config::check(std::isfinite(set.distance_gain) && set.distance_gain >= 0,
                context + ".distance_gain", "must be finite and >= 0");
  config::check(std::isfinite(set.distance_offset) && set.distance_offset >= 0,
                context + ".distance_offset", "must be finite and >= 0");
}

}  // namespace

Eigen::Vector4d SampcParams::input_lower_bound() const {
  return {thrust_min_m_s2, -roll_pitch_rate_max_rad_s, -roll_pitch_rate_max_rad_s,
          -yaw_rate_max_rad_s};
}

Eigen::Vector4d SampcParams::input_upper_bound() const {
  return {thrust_max_m_s2, roll_pitch_rate_max_rad_s, roll_pitch_rate_max_rad_s,
          yaw_rate_max_rad_s};
}

SampcParams SampcParams::load(config::YamlReader& reader) {
  SampcParams p;
  std::string mode = to_string(p.mode);
  reader.optional("mode", mode);
  p.mode = parse_mode_or_throw(mode, reader.context());
  reader.optional("horizon_steps", p.horizon_steps);
  reader.optional("step_s", p.step_s);
  reader.optional("control_period_s", p.control_period_s);
  reader.optional("e0", p.e0);
  reader.optional("e1", p.e1);
  reader.optional("e2_per_m2", p.e2_per_m2);
  reader.optional("e3", p.e3);
  reader.optional("thrust_min_m_s2", p.thrust_min_m_s2);
  reader.optional("thrust_max_m_s2", p.thrust_max_m_s2);
  reader.optional("roll_pitch_rate_max_rad_s", p.roll_pitch_rate_max_rad_s);
  reader.optional("yaw_rate_max_rad_s", p.yaw_rate_max_rad_s);
  load_weights(reader.child("transition_weights"), p.transition_weights, true);
  load_weights(reader.child("tracking_weights"), p.tracking_weights, false);
  reader.optional("tracking_feed_forward", p.tracking_feed_forward);
  reader.optional("terminal_weight_scale", p.terminal_weight_scale);
  reader.optional("yaw_hold_radius_m", p.yaw_hold_radius_m);
  reader.optional("yaw_reference_rate_rad_s", p.yaw_reference_rate_rad_s);
  reader.optional("custom_velocity_nodes", p.custom_velocity_nodes);
  reader.optional("eq30_acceleration_limit_m_s2", p.eq30_acceleration_limit_m_s2);
  reader.optional("switch_smoothing_s", p.switch_smoothing_s);
  reader.optional("switch_input_rate_weight", p.switch_input_rate_weight);
  reader.optional("transition_input_rate_weight", p.transition_input_rate_weight);
  reader.optional("yaw_flip_hysteresis_rad", p.yaw_flip_hysteresis_rad);
  reader.optional("yaw_reference_max_lag_rad", p.yaw_reference_max_lag_rad);
  reader.optional("max_sqp_iterations", p.max_sqp_iterations);
  reader.optional("cold_start_iterations", p.cold_start_iterations);
  reader.optional("frame_switch_iterations", p.frame_switch_iterations);
  reader.optional("sqp_step_tolerance", p.sqp_step_tolerance);
  reader.optional("max_qp_iterations", p.max_qp_iterations);
  p.intercept = InterceptParams::load(reader.child("intercept"));
  reader.optional("max_abs_position_m", p.max_abs_position_m);
  reader.optional("max_abs_speed_m_s", p.max_abs_speed_m_s);
  reader.optional("max_abs_angular_rate_rad_s", p.max_abs_angular_rate_rad_s);
  reader.reject_unknown_keys();
  p.validate();
  return p;
}

SampcParams SampcParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

SampcParams SampcParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "sampc", /*required=*/true);
  return load(reader);
}

void SampcParams::validate() const {
  const std::string c = "sampc";
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  config::check(horizon_steps >= 1 && horizon_steps <= kMaxHorizon, c + ".horizon_steps",
                "must be in [1, " + std::to_string(kMaxHorizon) + "]");
  config::check(positive(step_s), c + ".step_s", "must be > 0");
  config::check(positive(control_period_s), c + ".control_period_s", "must be > 0");
  config::check(std::isfinite(e0) && e0 >= 0, c + ".e0", "must be finite and >= 0");
  config::check(std::isfinite(e1) && e1 >= 0, c + ".e1", "must be finite and >= 0");
  config::check(std::isfinite(e2_per_m2) && e2_per_m2 <= 0, c + ".e2_per_m2",
                "must be finite and <= 0 (Qd grows as the UAV nears the UGV)");
  config::check(std::isfinite(e3) && e3 >= 0, c + ".e3", "must be finite and >= 0");
  config::check(positive(thrust_min_m_s2), c + ".thrust_min_m_s2", "must be > 0");
  config::check(std::isfinite(thrust_max_m_s2) && thrust_max_m_s2 > model::kGravity_m_s2 &&
                    thrust_min_m_s2 < model::kGravity_m_s2,
                c + ".thrust_max_m_s2", "thrust bounds must bracket hover (g)");
  config::check(positive(roll_pitch_rate_max_rad_s), c + ".roll_pitch_rate_max_rad_s",
                "must be > 0");
  config::check(positive(yaw_rate_max_rad_s), c + ".yaw_rate_max_rad_s", "must be > 0");
  validate_weights(transition_weights, c + ".transition_weights");
  validate_weights(tracking_weights, c + ".tracking_weights");
  config::check(positive(terminal_weight_scale), c + ".terminal_weight_scale", "must be > 0");
  config::check(std::isfinite(yaw_hold_radius_m) && yaw_hold_radius_m >= 0,
                c + ".yaw_hold_radius_m", "must be finite and >= 0");
  config::check(
      positive(yaw_reference_rate_rad_s) && yaw_reference_rate_rad_s <= yaw_rate_max_rad_s,
      c + ".yaw_reference_rate_rad_s", "must be > 0 and <= yaw_rate_max_rad_s");
  config::check(std::isfinite(yaw_flip_hysteresis_rad) && yaw_flip_hysteresis_rad >= 0 &&
                    yaw_flip_hysteresis_rad < 3.14,
                c + ".yaw_flip_hysteresis_rad", "must be in [0, pi)");
  config::check(std::isfinite(yaw_reference_max_lag_rad) && yaw_reference_max_lag_rad > 0 &&
                    yaw_reference_max_lag_rad < 1.5,
                c + ".yaw_reference_max_lag_rad", "must be in (0, 1.5)");
  config::check(custom_velocity_nodes >= 1 && custom_velocity_nodes <= horizon_steps,
                c + ".custom_velocity_nodes", "must be in [1, horizon_steps]");
  config::check(std::isfinite(eq30_acceleration_limit_m_s2) && eq30_acceleration_limit_m_s2 >= 0.0,
                c + ".eq30_acceleration_limit_m_s2", "must be >= 0 (0 disables)");
  config::check(
      std::isfinite(switch_smoothing_s) && switch_smoothing_s >= 0.0 && switch_smoothing_s <= 10.0,
      c + ".switch_smoothing_s", "must be in [0, 10]");
  config::check(
      switch_input_rate_weight.allFinite() && (switch_input_rate_weight.array() >= 0.0).all(),
      c + ".switch_input_rate_weight", "must be finite and >= 0");
  config::check(transition_input_rate_weight.allFinite() &&
                    (transition_input_rate_weight.array() >= 0.0).all(),
                c + ".transition_input_rate_weight", "must be finite and >= 0");
  intercept.validate(c + ".intercept");
  config::check(intercept.velocity_nodes >= 1 && intercept.velocity_nodes <= horizon_steps,
                c + ".intercept.velocity_nodes", "must be in [1, horizon_steps]");
  config::check(max_sqp_iterations >= 1, c + ".max_sqp_iterations", "must be >= 1");
  config::check(cold_start_iterations >= 1, c + ".cold_start_iterations", "must be >= 1");
  config::check(frame_switch_iterations >= 1, c + ".frame_switch_iterations", "must be >= 1");
  config::check(positive(sqp_step_tolerance), c + ".sqp_step_tolerance", "must be > 0");
  config::check(max_qp_iterations >= 1, c + ".max_qp_iterations", "must be >= 1");
  config::check(positive(max_abs_position_m), c + ".max_abs_position_m", "must be > 0");
  config::check(positive(max_abs_speed_m_s), c + ".max_abs_speed_m_s", "must be > 0");
  config::check(positive(max_abs_angular_rate_rad_s), c + ".max_abs_angular_rate_rad_s",
                "must be > 0");
}

}  // namespace cover::sampc
