#include "cover/sim/scenario.hpp"
#include "cover/mission/task_file.hpp"

#include <filesystem>

#include "cover/sim/seeding.hpp"
#include "cover/vocabulary/fleet_size.hpp"

namespace cover::sim {

Scenario Scenario::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

Scenario Scenario::from_yaml(const YAML::Node& document, const std::string& path) {
  config::YamlReader root(document, path);
  Scenario scenario;
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
    scenario.task = mission::read_task(task);
  }
  YAML::Node list;
  root.optional("extra_uavs", list);
  if (root.has("extra_uavs")) {
    config::check(list.IsSequence(), path + ".extra_uavs", "must be a list");
    for (std::size_t i = 0; i < list.size(); ++i) {
      config::YamlReader entry(list[i], path + ".extra_uavs[" + std::to_string(i) + "]");
      ExtraUav extra;
      std::string task_file;
      entry.require("task_file", task_file);
      config::load_fields(extra, entry);
      const auto resolved = std::filesystem::path(path).parent_path() / task_file;
      extra.task =
          mission::load_task_file(resolved.string(), static_cast<int>(scenario.world.ugvs.size()));
      scenario.extra_uavs.push_back(extra);
    }
  }
  config::load_fields(scenario, root);
  scenario.validate();
  return scenario;
}

const mission::Task& Scenario::task_of(int uav) const {
  return uav == 0 ? task : extra_uavs.at(static_cast<std::size_t>(uav - 1)).task;
}

WorldParams Scenario::world_of(int uav) const {
  if (uav == 0) return world;
  const ExtraUav& extra = extra_uavs.at(static_cast<std::size_t>(uav - 1));
  WorldParams w = world;
  w.uav_initial.start_on_ugv = extra.start_on_ugv;
  w.payload.attached_at_start = extra.payload_attached;
  // Independent sensor noise per UAV; UAV 0 keeps the world's seed (the harness's run).
  w.seed = derive_seed(world.seed, 1000 + static_cast<std::uint64_t>(uav));
  return w;
}

void Scenario::validate() const {
  config::check_fields(*this, "scenario '" + name + "'");
  world.validate("scenario '" + name + "'.sim");
  mission::validate_task(task, static_cast<int>(world.ugvs.size()));
  config::check(uav_count() <= fleet::kMaxUavs, "scenario '" + name + "'.extra_uavs",
                "at most " + std::to_string(fleet::kMaxUavs - 1) + " (" +
                    std::to_string(fleet::kMaxUavs) + " UAVs)");
  for (int u = 1; u < uav_count(); ++u) {
    config::check_fields(extra_uavs[static_cast<std::size_t>(u - 1)],
                         "scenario '" + name + "'.extra_uavs[" + std::to_string(u - 1) + "]");
    mission::validate_task(task_of(u), static_cast<int>(world.ugvs.size()));
    config::check(
        task_of(u).uav_id == u, "scenario '" + name + "'.extra_uavs",
        "entry " + std::to_string(u - 1) + " must fly a task with uav_id " + std::to_string(u));
    world_of(u).validate("scenario '" + name + "'.extra_uavs");
  }
}

void Scenario::keep_fleet(int uavs, int ugvs) {
  const int scenario_ugvs = static_cast<int>(world.ugvs.size());
  config::check(uavs >= 1 && uavs <= uav_count(), "--uavs " + std::to_string(uavs),
                "scenario '" + name + "' has " + std::to_string(uav_count()) + " UAV(s)");
  config::check(ugvs >= 1 && ugvs <= scenario_ugvs, "--ugvs " + std::to_string(ugvs),
                "scenario '" + name + "' has " + std::to_string(scenario_ugvs) + " UGV(s)");
  extra_uavs.resize(static_cast<std::size_t>(uavs - 1));
  world.ugvs.resize(static_cast<std::size_t>(ugvs));
  for (int u = 0; u < uavs; ++u) {
    config::check(world_of(u).uav_initial.start_on_ugv < ugvs, "--ugvs " + std::to_string(ugvs),
                  "UAV " + std::to_string(u) + " starts on the deck of a UGV left out");
  }
  validate();
}

std::string scenario_path(const std::string& name) {
  return config::default_config_dir() + "/scenarios/" + name + ".yaml";
}

}  // namespace cover::sim
