#include "sim_process_params.hpp"

namespace cover::sim {

SimProcessParams SimProcessParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

SimProcessParams SimProcessParams::from_yaml(const YAML::Node& document,
                                             const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "sim_process", true);
  SimProcessParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void SimProcessParams::validate() const {
  config::check_fields(*this, "sim_process");
}

}  // namespace cover::sim
