#include "cover/sim/mocap/mocap_server_params.hpp"

namespace cover::sim::mocap {

MocapServerParams MocapServerParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

MocapServerParams MocapServerParams::from_yaml(const YAML::Node& document,
                                               const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "mocap", false);
  MocapServerParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void MocapServerParams::validate() const {
  config::check_fields(*this, "mocap");
  config::check(!uav_prefix.empty() && !ugv_prefix.empty() && uav_prefix != ugv_prefix,
                "mocap.uav_prefix", "the prefixes must be non-empty and differ");
}

}  // namespace cover::sim::mocap
