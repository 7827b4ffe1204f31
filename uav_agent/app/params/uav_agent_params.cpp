#include "uav_agent_params.hpp"

namespace cover::uav_agent {

UavAgentParams UavAgentParams::load(cover::config::YamlReader& reader) {
  UavAgentParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

UavAgentParams UavAgentParams::load_file(const std::string& path) {
  return from_yaml(cover::config::load_yaml_file(path), path);
}

UavAgentParams UavAgentParams::from_yaml(const YAML::Node& document, const std::string& source) {
  auto reader = cover::config::open_section(document, source, "uav_agent", /*required=*/true);
  return load(reader);
}

void UavAgentParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
}

}  // namespace cover::uav_agent
