#pragma once

#include <string>
#include <vector>

#include "cover/config/param_fields.hpp"
#include "cover/sim/world_params.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::sim {

// A further UAV in the same world (cover-sim flies up to 4): its own plant, sensors and
// payload, started on `start_on_ugv`'s deck, flying its own task.
struct ExtraUav {
  mission::Task task;
  int start_on_ugv = 0;
  bool payload_attached = false;

  // Its fields (config/param_fields.hpp) but for `task_file`, the task's path relative to
  // the scenario file (required), which Scenario::from_yaml reads itself.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("start_on_ugv", self.start_on_ugv,
          Field("", "index of the UGV whose deck it starts on; -1: at sim.uav.initial.position_m")
              .at_least(-1.0));
    visit("payload_attached", self.payload_attached, Field("", "it carries a parcel at start"));
  }
};

// One closed-loop experiment: a simulated world (the sim's world YAML format, under `sim:`)
// and the task the UAV flies in it. Files live in config/scenarios/.
struct Scenario {
  std::string name = "scenario";
  std::string description;
  WorldParams world;
  mission::Task task;
  // The run stops (unsuccessfully) at this simulated time if the task is not done.
  double max_duration_s = 120.0;
  // After the task completes, keep simulating this long (a disarmed UAV drops and settles
  // on the deck) before measuring the landing error.
  double settle_time_s = 1.0;
  // UAVs 1.. (UAV 0 is `world` + `task`); the in-process harness flies UAV 0 only.
  std::vector<ExtraUav> extra_uavs;

  // The scenario's own fields (config/param_fields.hpp); `sim`, `task` / `task_file` and
  // `extra_uavs` are read by from_yaml itself.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("name", self.name, Field("", "label in reports and plots"));
    visit("description", self.description, Field("", "what the scenario flies"));
    visit("max_duration_s", self.max_duration_s,
          Field("s", "run cut-off: unsuccessful if the task is not done by then")
              .above(0.0)
              .at_most(3600.0));
    visit("settle_time_s", self.settle_time_s,
          Field("s", "simulated time after completion before the landing error is measured")
              .at_least(0.0)
              .at_most(60.0));
  }

  int uav_count() const { return 1 + static_cast<int>(extra_uavs.size()); }
  const mission::Task& task_of(int uav) const;
  // UAV `uav`'s world: the same UGVs, its start and payload, its own sensor noise streams.
  WorldParams world_of(int uav) const;

  // Keys: name, description, max_duration_s, settle_time_s, sim (world format), and either
  // task (inline, task format) or task_file (path relative to the scenario file).
  static Scenario load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml), as if read from `path`:
  // it names the document in errors and its task files are relative to its folder.
  static Scenario from_yaml(const YAML::Node& document, const std::string& path);
  void validate() const;
  // Keeps UAVs 0..uavs-1 and UGVs 0..ugvs-1 (cover-sim --uavs / --ugvs: a fleet's size set
  // at start, a smaller part of a bigger scenario). Throws ConfigError for a count outside
  // 1..the scenario's, or when a kept UAV's task or deck names a UGV left out.
  void keep_fleet(int uavs, int ugvs);
};

// config/scenarios/<name>.yaml
std::string scenario_path(const std::string& name);

}  // namespace cover::sim
