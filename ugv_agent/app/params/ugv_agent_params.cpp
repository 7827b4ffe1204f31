#include "ugv_agent_params.hpp"

namespace cover::ugv {

UgvAgentParams UgvAgentParams::load(cover::config::YamlReader& reader) {
  UgvAgentParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

UgvAgentParams UgvAgentParams::load_file(const std::string& path) {
  return from_yaml(cover::config::load_yaml_file(path), path);
}

UgvAgentParams UgvAgentParams::from_yaml(const YAML::Node& document, const std::string& source) {
  auto reader = cover::config::open_section(document, source, "ugv_agent", /*required=*/true);
  return load(reader);
}

void UgvAgentParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
}

}  // namespace cover::ugv
