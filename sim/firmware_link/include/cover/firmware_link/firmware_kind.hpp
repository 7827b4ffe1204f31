#pragma once

#include <memory>
#include <string>

#include "cover/firmware_link/firmware_link.hpp"
#include "cover/vocabulary/autopilot.hpp"

namespace cover::firmware_link {

// Where each real firmware expects COVER's physics (cover::firmware::physics_port): UAV u's
// link is at the base port plus u times the firmware's stride (PX4 1, ArduPilot 10, as SITL's
// -I N shifts its ports). A base other than the firmware's own moves every UAV's link.
int default_port_base(Autopilot autopilot);
int firmware_port(Autopilot autopilot, int port_base, int uav);
// The motor-level UAV file that matches the firmware's airframe (in config/sim/).
std::string firmware_uav_file_name(Autopilot autopilot);

// The link for UAV `uav` (bound at construction; throws std::runtime_error or
// std::system_error when its port cannot be bound).
std::unique_ptr<FirmwareLink> make_link(Autopilot autopilot, int uav, int port_base, Pacing pacing);

}  // namespace cover::firmware_link
