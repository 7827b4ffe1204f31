#include "cover/sim/firmware_uav_params.hpp"

#include "cover/config/yaml_reader.hpp"

namespace cover::sim {

FirmwareUavParams FirmwareUavParams::load_file(const std::string& path, double physics_rate_hz) {
  config::YamlReader reader = config::open_section(path, "firmware_uav", true);
  FirmwareUavParams p;
  config::load_fields(p, reader);
  p.validate(reader.context(), physics_rate_hz);
  return p;
}

void FirmwareUavParams::validate(const std::string& context, double physics_rate_hz) const {
  plant.validate(context + ".plant");
  sensors.validate(context + ".sensors", physics_rate_hz);
}

}  // namespace cover::sim
