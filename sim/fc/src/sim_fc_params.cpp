#include "cover/sim/fc/sim_fc_params.hpp"

namespace cover::sim::fc {

using config::check;

SimFcParams SimFcParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

SimFcParams SimFcParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "sim_fc", true);
  SimFcParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void SimFcParams::validate() const {
  config::check_fields(*this, "sim_fc");
  const bool overlap =
      ugv_system_id_base <= system_id_base + 3 && system_id_base <= ugv_system_id_base + 7;
  check(!overlap, "sim_fc.ugv_system_id_base", "must not overlap the UAVs' system ids");
  check(battery.cell_full_v > battery.cell_empty_v, "sim_fc.battery.cell_full_v",
        "must exceed cell_empty_v");
}

}  // namespace cover::sim::fc
