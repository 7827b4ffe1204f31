#pragma once

#include <string>

#include "cover/config/param_fields.hpp"
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
  // Real firmware (--firmware): the world waits, its UGVs still, until every UAV's firmware
  // reports its attitude estimate valid (PX4 aligns only below 15 deg/s); after this much
  // of the firmware's time without it the run stops with an error naming the UAV, s.
  double firmware_align_timeout_s = 60.0;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("offboard_timeout_s", self.offboard_timeout_s,
          Field("s", "no fresh command for this long: the simulated FC levels, descends, disarms")
              .above(0.0));
    visit("loss_descent_rate_m_s", self.loss_descent_rate_m_s,
          Field("m/s", "descent rate after the offboard loss").above(0.0).at_most(3.0));
    visit("stall_timeout_s", self.stall_timeout_s,
          Field("s", "lockstep: a tick's commands missing this long stop the run").above(0.0));
    visit("startup_timeout_s", self.startup_timeout_s,
          Field("s", "every UAV agent must have answered the first tick by then").above(0.0));
    visit("control_rate_hz", self.control_rate_hz,
          Field("Hz", "the agents' control rate, one tick each").above(0.0).at_most(1000.0));
    visit("firmware_align_timeout_s", self.firmware_align_timeout_s,
          Field("s", "real firmware: its time to align on a still deck before the world starts")
              .above(0.0)
              .at_most(600.0));
  }

  static SimProcessParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static SimProcessParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::sim
