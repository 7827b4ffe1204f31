#pragma once

#include <memory>
#include <optional>
#include <string>

#include "cover/firmware_link/firmware_link.hpp"

namespace cover::firmware_link {

// The real firmwares COVER's simulator is the physics of, and where each expects it.
enum class FirmwareKind { Px4, ArduPilot };

// "px4" / "ardupilot"; nullopt for anything else.
std::optional<FirmwareKind> parse_firmware_kind(const std::string& text);
// "PX4", "ArduCopter".
const char* firmware_name(FirmwareKind kind);
// PX4's simulator_mavlink: TCP 4560 + instance. ArduPilot's JSON backend: UDP 9002 + 10 x
// instance (SITL's -I N shifts its ports by 10).
int default_port_base(FirmwareKind kind);
int firmware_port(FirmwareKind kind, int port_base, int uav);
// The motor-level UAV file that matches the firmware's airframe (in config/sim/).
std::string firmware_uav_file_name(FirmwareKind kind);

// The link for UAV `uav` (bound at construction; throws std::runtime_error or
// std::system_error when its port cannot be bound).
std::unique_ptr<FirmwareLink> make_link(FirmwareKind kind, int uav, int port_base, Pacing pacing);

}  // namespace cover::firmware_link
