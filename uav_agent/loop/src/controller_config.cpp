#include "cover/uav/controller_config.hpp"

#include "cover/config/yaml_reader.hpp"

namespace cover::uav {

ControllerConfig ControllerConfig::load(const std::string& config_dir) {
  ControllerConfig c;
  c.mission = mission::MissionParams::load_file(config_dir + "/mission.yaml");
  c.planner = planner::PlannerParams::load_file(config_dir + "/planner.yaml");
  c.sampc = sampc::SampcParams::load_file(config_dir + "/sampc.yaml");
  c.validate();
  return c;
}

ControllerConfig ControllerConfig::load_default(sampc::Mode mode) {
  ControllerConfig c = load(config::default_config_dir());
  c.sampc.mode = mode;
  c.validate();
  return c;
}

void ControllerConfig::validate() const {
  mission.validate();
  planner.validate();
  sampc.validate();
}

}  // namespace cover::uav
