#include "cover/uav/controller_config.hpp"

#include "cover/config/format_number.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/vocabulary/motion_limits.hpp"

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
  check_agreement();
}

// What the three files hold twice, or bound for each other, must agree.
void ControllerConfig::check_agreement() const {
  mission::check_control_period(mission, sampc.control_period_s,
                                "sampc.yaml: sampc.control_period_s");
  // Every task Task::validate accepts must be plannable: the planner's sanity bounds may
  // not be tighter than a task's (mission/motion_limits.hpp).
  config::check(planner.max_limit_m_s >= mission::kPlausibleVmax_m_s,
                "planner.yaml: planner.max_limit_m_s",
                config::format_number(planner.max_limit_m_s) + " m/s is below " +
                    config::format_number(mission::kPlausibleVmax_m_s) +
                    " m/s, the largest vmax_m_s a task may have (mission/motion_limits.hpp)");
  config::check(planner.max_limit_m_s2 >= mission::kPlausibleAmax_m_s2,
                "planner.yaml: planner.max_limit_m_s2",
                config::format_number(planner.max_limit_m_s2) + " m/s^2 is below " +
                    config::format_number(mission::kPlausibleAmax_m_s2) +
                    " m/s^2, the largest amax_m_s2 a task may have (mission/motion_limits.hpp)");
}

}  // namespace cover::uav
