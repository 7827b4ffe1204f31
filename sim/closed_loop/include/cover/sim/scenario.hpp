#pragma once

#include <string>

#include "cover/mission/task.hpp"
#include "cover/sim/world_params.hpp"

namespace cover::sim {

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

  // Keys: name, description, max_duration_s, settle_time_s, sim (world format), and either
  // task (inline, task format) or task_file (path relative to the scenario file).
  static Scenario load_file(const std::string& path);
  void validate() const;
};

// config/scenarios/<name>.yaml
std::string scenario_path(const std::string& name);

}  // namespace cover::sim
