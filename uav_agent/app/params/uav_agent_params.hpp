#pragma once

#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"

namespace cover::uav_agent {

// The UAV agent's own settings: section `uav_agent` of config/uav_agent.yaml (documents each
// key). The controller's are in mission.yaml, planner.yaml and sampc.yaml.
struct UavAgentParams {
  double status_period_s = 0.1;  // cover/uav/<u>/status at 10 Hz
  // Lockstep: how long a tick waits for its relative states and IMU before stepping anyway.
  double input_wait_s = 2.0;
  // No tick (lockstep) or no fresh relative state (realtime) for this long: keep going
  // (failsafe commands), but say so.
  double silence_warning_s = 2.0;
  // Lockstep: before answering the first tick, wait this long for the inputs' publishers.
  double connect_timeout_s = 20.0;
  // The bridge publishes at 10 Hz: silent this long (wall clock) counts as not ready.
  double fc_stale_after_s = 1.0;
  // Realtime: wake this long before the next relative state is due (a control period after
  // the last) to rehearse the step's feedback (UavLoop::rehearse): after 10 ms asleep the
  // feedback otherwise runs on caches the other processes emptied; 0: no rehearsal.
  double rehearsal_lead_s = 0.5e-3;
  // Realtime, after the rehearsal: wait for the relative state on the CPU (no sleep) for at
  // most this long, so that nothing else runs on the control thread's core between the
  // rehearsal and the measurement; then sleep as before. Costs this much CPU per period
  // (5 % of a core at 0.5 ms); 0: sleep at once. Only with the control thread placed on
  // control_cpu (spinning on the DDS threads' core would hold off the sample awaited):
  // otherwise ignored, and the agent says so.
  double spin_after_rehearsal_s = 0.0;
  // Realtime: the control thread's CPU; the process's other threads (DDS receive threads,
  // the planner) run on the other CPUs it may use. -1: every thread where the process was
  // started (cpu_affinity of the launch file).
  int control_cpu = -1;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using cover::config::Field;
    visit("status_period_s", self.status_period_s,
          Field("s", "cover/uav/<u>/status period").above(0.0).at_most(10.0));
    visit("input_wait_s", self.input_wait_s,
          Field("s", "lockstep: a tick waits this long for its inputs, then steps on what came")
              .above(0.0)
              .at_most(60.0));
    visit(
        "silence_warning_s", self.silence_warning_s,
        Field("s", "no tick / no fresh relative state this long: logged (failsafe commands go on)")
            .above(0.0)
            .at_most(600.0));
    visit("connect_timeout_s", self.connect_timeout_s,
          Field("s", "lockstep: wait this long for the inputs' publishers before the first tick")
              .above(0.0)
              .at_most(600.0));
    visit("fc_stale_after_s", self.fc_stale_after_s,
          Field("s", "the flight-controller bridge silent this long counts as not ready")
              .above(0.0)
              .at_most(60.0));
    visit("rehearsal_lead_s", self.rehearsal_lead_s,
          Field("s", "realtime: rehearse the feedback this long before the relative state is due")
              .at_least(0.0)
              .below(5e-3));
    visit("spin_after_rehearsal_s", self.spin_after_rehearsal_s,
          Field("s", "realtime: after the rehearsal, wait for the state on the CPU this long")
              .at_least(0.0)
              .at_most(5e-3));
    visit(
        "control_cpu", self.control_cpu,
        Field("", "realtime: the control thread's CPU, the other threads elsewhere; -1: as started")
            .at_least(-1.0)
            .at_most(1023.0));
  }

  static UavAgentParams load(cover::config::YamlReader& reader);
  // Section `uav_agent` of `path`; throws ConfigError naming the file and key.
  static UavAgentParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static UavAgentParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate(const std::string& context = "uav_agent") const;
};

}  // namespace cover::uav_agent
