#pragma once

#include <string>

#include "cover/config/yaml_reader.hpp"

namespace cover::sim {

// cover-sim's own settings (config/sim/sim_process.yaml, section `sim_process`).
struct SimProcessParams {
  // The simulated flight controller's offboard-loss failsafe (PX4's COM_OF_LOSS_T): no
  // fresh command for this long, s, and it levels, descends and disarms on contact.
  double offboard_timeout_s = 0.5;
  double loss_descent_rate_m_s = 0.5;
  // Lockstep: a tick whose commands have not all arrived after this long stops the run
  // with an error naming the missing UAV agent, s.
  double stall_timeout_s = 5.0;
  // Every UAV agent must have discovered the simulator and answered the first tick by
  // then, s (discovery can take a while; later ticks get stall_timeout_s).
  double startup_timeout_s = 30.0;
  double control_rate_hz = 100.0;

  static SimProcessParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static SimProcessParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::sim
