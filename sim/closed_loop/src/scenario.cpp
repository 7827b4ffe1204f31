#include "cover/sim/scenario.hpp"

#include <cmath>
#include <filesystem>

namespace cover::sim {

Scenario Scenario::load_file(const std::string& path) {
  config::YamlReader root(config::load_yaml_file(path), path);
  Scenario scenario;
  root.optional("name", scenario.name);
  root.optional("description", scenario.description);
  root.optional("max_duration_s", scenario.max_duration_s);
  root.optional("settle_time_s", scenario.settle_time_s);
  config::YamlReader world = root.child("sim");
  scenario.world = WorldParams::load(world);
  if (root.has("task_file")) {
    std::string task_file;
    root.require("task_file", task_file);
    const std::filesystem::path resolved = std::filesystem::path(path).parent_path() / task_file;
    scenario.task =
        mission::load_task_file(resolved.string(), static_cast<int>(scenario.world.ugvs.size()));
  } else {
    config::YamlReader task = root.child("task");
    scenario.task = mission::Task::load(task);
  }
  root.reject_unknown_keys();
  scenario.validate();
  return scenario;
}

void Scenario::validate() const {
  world.validate("scenario '" + name + "'.sim");
  task.validate(static_cast<int>(world.ugvs.size()));
  config::check(std::isfinite(max_duration_s) && max_duration_s > 0.0 && max_duration_s <= 3600.0,
                "scenario '" + name + "'.max_duration_s", "must be in (0, 3600]");
  config::check(std::isfinite(settle_time_s) && settle_time_s >= 0.0 && settle_time_s <= 60.0,
                "scenario '" + name + "'.settle_time_s", "must be in [0, 60]");
}

std::string scenario_path(const std::string& name) {
  return config::default_config_dir() + "/scenarios/" + name + ".yaml";
}

}  // namespace cover::sim
