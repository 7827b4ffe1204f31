#include "cover/fc_bridge/fc_bridge_params.hpp"

#include <cmath>

namespace cover::fc_bridge {

FcBridgeParams FcBridgeParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

FcBridgeParams FcBridgeParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "fc_bridge", true);
  FcBridgeParams p;
  reader.optional("hover_thrust", p.hover_thrust);
  reader.optional("hover_thrust_min", p.hover_thrust_min);
  reader.optional("hover_thrust_max", p.hover_thrust_max);
  reader.optional("hover_thrust_initial_std", p.hover_thrust_initial_std);
  reader.optional("hover_thrust_noise_per_sqrt_s", p.hover_thrust_noise_per_sqrt_s);
  reader.optional("accel_noise_m_s2", p.accel_noise_m_s2);
  reader.optional("estimator_min_thrust", p.estimator_min_thrust);
  reader.optional("cmd_timeout_s", p.cmd_timeout_s);
  reader.optional("heartbeat_timeout_s", p.heartbeat_timeout_s);
  reader.optional("ack_timeout_s", p.ack_timeout_s);
  reader.optional("command_retries", p.command_retries);
  reader.optional("offboard_stream_s", p.offboard_stream_s);
  reader.optional("state_rate_hz", p.state_rate_hz);
  reader.optional("system_id", p.system_id);
  reader.optional("component_id", p.component_id);
  reader.optional("auto_arm", p.auto_arm);
  reader.optional("gravity_m_s2", p.gravity_m_s2);
  reader.reject_unknown_keys();
  p.validate();
  return p;
}

void FcBridgeParams::validate() const {
  auto in = [](double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  config::check(in(hover_thrust_min, 0.01, 0.99), "fc_bridge.hover_thrust_min",
                "must be in [0.01, 0.99]");
  config::check(in(hover_thrust_max, hover_thrust_min, 0.99), "fc_bridge.hover_thrust_max",
                "must be in [hover_thrust_min, 0.99]");
  config::check(in(hover_thrust, hover_thrust_min, hover_thrust_max), "fc_bridge.hover_thrust",
                "must be in [hover_thrust_min, hover_thrust_max]");
  config::check(in(hover_thrust_initial_std, 1e-4, 1.0), "fc_bridge.hover_thrust_initial_std",
                "must be in [1e-4, 1]");
  config::check(in(hover_thrust_noise_per_sqrt_s, 0.0, 1.0),
                "fc_bridge.hover_thrust_noise_per_sqrt_s", "must be in [0, 1]");
  config::check(in(accel_noise_m_s2, 0.01, 50.0), "fc_bridge.accel_noise_m_s2",
                "must be in [0.01, 50]");
  config::check(in(estimator_min_thrust, 0.0, 0.9), "fc_bridge.estimator_min_thrust",
                "must be in [0, 0.9]");
  config::check(in(cmd_timeout_s, 0.01, 1.0), "fc_bridge.cmd_timeout_s",
                "must be in [0.01, 1] (PX4's own offboard loss is 1 s)");
  config::check(in(heartbeat_timeout_s, 0.5, 30.0), "fc_bridge.heartbeat_timeout_s",
                "must be in [0.5, 30] (autopilots send HEARTBEAT at 1 Hz)");
  config::check(in(ack_timeout_s, 0.01, 5.0), "fc_bridge.ack_timeout_s", "must be in [0.01, 5]");
  config::check(command_retries >= 0 && command_retries <= 20, "fc_bridge.command_retries",
                "must be in [0, 20]");
  config::check(in(offboard_stream_s, 0.0, 30.0), "fc_bridge.offboard_stream_s",
                "must be in [0, 30]");
  config::check(positive(state_rate_hz) && state_rate_hz >= 5.0 && state_rate_hz <= 100.0,
                "fc_bridge.state_rate_hz", "must be in [5, 100]");
  config::check(system_id >= 0 && system_id <= 255, "fc_bridge.system_id",
                "must be in [0, 255] (0: the autopilot's)");
  config::check(component_id >= 1 && component_id <= 255, "fc_bridge.component_id",
                "must be in [1, 255]");
  config::check(in(gravity_m_s2, 9.0, 10.5), "fc_bridge.gravity_m_s2", "must be in [9, 10.5]");
}

}  // namespace cover::fc_bridge
