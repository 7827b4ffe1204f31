#include "cover/firmware_link/firmware_kind.hpp"


#include "cover/firmware_link/ardupilot_json_link.hpp"
#include "cover/firmware_link/px4_hil_link.hpp"

namespace cover::firmware_link {

std::optional<FirmwareKind> parse_firmware_kind(const std::string& text) {
  if (text == "px4") return FirmwareKind::Px4;
  if (text == "ardupilot") return FirmwareKind::ArduPilot;
  return std::nullopt;
}

const char* firmware_name(FirmwareKind kind) {
  return kind == FirmwareKind::Px4 ? "PX4" : "ArduCopter";
}

int default_port_base(FirmwareKind kind) {
  return kind == FirmwareKind::Px4 ? 4560 : 9002;
}

int firmware_port(FirmwareKind kind, int port_base, int uav) {
  return kind == FirmwareKind::Px4 ? port_base + uav : port_base + 10 * uav;
}

std::string firmware_uav_file_name(FirmwareKind kind) {
  return kind == FirmwareKind::Px4 ? "firmware_uav_px4.yaml" : "firmware_uav_arducopter.yaml";
}

std::unique_ptr<FirmwareLink> make_link(FirmwareKind kind, int uav, int port_base, Pacing pacing) {
  const int port = firmware_port(kind, port_base, uav);
  if (kind == FirmwareKind::Px4) {
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
