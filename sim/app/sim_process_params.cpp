#include "sim_process_params.hpp"

#include <cmath>

namespace cover::sim {

SimProcessParams SimProcessParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

SimProcessParams SimProcessParams::from_yaml(const YAML::Node& document,
                                             const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "sim_process", true);
  SimProcessParams p;
  reader.optional("offboard_timeout_s", p.offboard_timeout_s);
  reader.optional("loss_descent_rate_m_s", p.loss_descent_rate_m_s);
  reader.optional("stall_timeout_s", p.stall_timeout_s);
  reader.optional("startup_timeout_s", p.startup_timeout_s);
  reader.optional("control_rate_hz", p.control_rate_hz);
  reader.reject_unknown_keys();
  p.validate();
  return p;
}

void SimProcessParams::validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  config::check(positive(offboard_timeout_s), "sim_process.offboard_timeout_s", "must be > 0");
  config::check(positive(loss_descent_rate_m_s) && loss_descent_rate_m_s <= 3.0,
                "sim_process.loss_descent_rate_m_s", "must be in (0, 3]");
  config::check(positive(stall_timeout_s), "sim_process.stall_timeout_s", "must be > 0");
  config::check(positive(startup_timeout_s), "sim_process.startup_timeout_s", "must be > 0");
  config::check(positive(control_rate_hz) && control_rate_hz <= 1000.0,
                "sim_process.control_rate_hz", "must be in (0, 1000]");
}

}  // namespace cover::sim
