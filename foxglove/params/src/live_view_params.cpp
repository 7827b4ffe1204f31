#include "cover/foxglove/live_view_params.hpp"

namespace cover::foxglove {

LiveViewParams LiveViewParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

LiveViewParams LiveViewParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "foxglove", false);
  LiveViewParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void LiveViewParams::validate() const {
  config::check_fields(*this, "foxglove");
}

}  // namespace cover::foxglove
