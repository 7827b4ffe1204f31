#include "cover/firmware_link/firmware_kind.hpp"

#include "cover/firmware/sitl_ports.hpp"
#include "cover/firmware_link/ardupilot_json_link.hpp"
#include "cover/firmware_link/px4_hil_link.hpp"

namespace cover::firmware_link {

int default_port_base(Autopilot autopilot) {
  return firmware::physics_port(autopilot, 0);
}

int firmware_port(Autopilot autopilot, int port_base, int uav) {
  return port_base + firmware::physics_port(autopilot, uav) - firmware::physics_port(autopilot, 0);
}

std::string firmware_uav_file_name(Autopilot autopilot) {
  return autopilot == Autopilot::Px4 ? "firmware_uav_px4.yaml" : "firmware_uav_arducopter.yaml";
}

std::unique_ptr<FirmwareLink> make_link(Autopilot autopilot, int uav, int port_base,
                                        Pacing pacing) {
  const int port = firmware_port(autopilot, port_base, uav);
  if (autopilot == Autopilot::Px4) {
    Px4HilConfig config;
    config.port = static_cast<std::uint16_t>(port);
    config.pacing = pacing;
    return std::make_unique<Px4HilLink>(config);
  }
  ArduPilotJsonLinkOptions options;
  options.port = port;
  options.pacing = pacing;
  return std::make_unique<ArduPilotJsonLink>(options);
}

}  // namespace cover::firmware_link
