#include "cover/fc_bridge/fc_bridge_params.hpp"

namespace cover::fc_bridge {

FcBridgeParams FcBridgeParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

FcBridgeParams FcBridgeParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "fc_bridge", true);
  FcBridgeParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void FcBridgeParams::validate() const {
  const std::string ctx = "fc_bridge";
  config::check_fields(*this, ctx);
  config::check(hover_thrust_max >= hover_thrust_min, ctx + ".hover_thrust_max",
                "must be >= hover_thrust_min");
  config::check(hover_thrust >= hover_thrust_min && hover_thrust <= hover_thrust_max,
                ctx + ".hover_thrust", "must be in [hover_thrust_min, hover_thrust_max]");
}

}  // namespace cover::fc_bridge
