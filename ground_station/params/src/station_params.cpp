#include "cover/ground_station/station_params.hpp"

namespace cover::ground_station {

StationParams StationParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

StationParams StationParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "ground_station", false);
  StationParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void StationParams::validate() const {
  config::check_fields(*this, "ground_station");
}

}  // namespace cover::ground_station
