#pragma once

#include <string>

#include "cover/mission/mission_params.hpp"
#include "cover/planner/planner_params.hpp"
#include "cover/sampc/sampc_params.hpp"

namespace cover::uav {

// Everything the UAV's controller needs to start: config/{mission,planner,sampc}.yaml.
struct ControllerConfig {
  mission::MissionParams mission;
  planner::PlannerParams planner;
  sampc::SampcParams sampc;

  // Loads the three files from `config_dir`; throws config::ConfigError naming the file
  // and key.
  static ControllerConfig load(const std::string& config_dir);
  // The shipped defaults (config/), with SAMPC's method set to `mode`.
  static ControllerConfig load_default(sampc::Mode mode);
  // Each file's own validation, then check_agreement().
  void validate() const;
  // What the files hold twice or bound for each other: the control period (mission's and
  // SAMPC's), the planner's limit bounds against a task's. Throws config::ConfigError
  // naming both files and keys.
  void check_agreement() const;
};

}  // namespace cover::uav
