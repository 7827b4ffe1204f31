#include "cover/mission/mission_params.hpp"

#include <cmath>

#include "cover/config/format_number.hpp"

namespace cover::mission {

const char* to_string(AbortAction action) {
  switch (action) {
    case AbortAction::Hover:
      return "hover";
    case AbortAction::Land:
      return "land";
  }
  return "unknown";
}

const char* to_string(TransitionReference reference) {
  switch (reference) {
    case TransitionReference::Planned:
      return "planned";
    case TransitionReference::RadialApproach:
      return "radial-approach";
  }
  return "unknown";
}

MissionParams MissionParams::load(config::YamlReader& reader) {
  MissionParams params;
  config::load_fields(params, reader);
  params.validate();
  return params;
}

MissionParams MissionParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

MissionParams MissionParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader section =
      config::open_section(document, source, "mission", /*required=*/false);
  return load(section);
}

void MissionParams::validate() const {
  config::check_fields(*this, "mission");
}

void check_control_period(const MissionParams& mission, double other_period_s,
                          const std::string& other) {
  // Equal to a nanosecond: both are written as decimals of the same period (0.01 s, 100 Hz).
  if (std::abs(other_period_s - mission.control_period_s) <= 1e-9) return;
  throw config::ConfigError(other + " (" + config::format_number(other_period_s) +
                            " s) disagrees with " + kMissionControlPeriodKey + " (" +
                            config::format_number(mission.control_period_s) +
                            " s): the control period is one; set them equal");
}

}  // namespace cover::mission
