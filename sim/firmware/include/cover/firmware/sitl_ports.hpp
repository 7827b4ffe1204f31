#pragma once
// The ports a real firmware's SITL instance N uses on this host, as the firmware numbers
// them (PX4: ROMFS init.d-posix/px4-rc.mavlink; ArduPilot: `arducopter -I N` adds 10 N to
// its base ports). Two instances with one N, or anything else on these ports, collide.
#include <vector>

#include "cover/vocabulary/autopilot.hpp"

namespace cover::firmware {

// Both send their companion (onboard) link to UDP 127.0.0.1:14540 + N: PX4 by its start
// script, ArduCopter because the test starts it with --serial1 udpclient:127.0.0.1:14540+N.
// PX4 sends every instance above 9 to 14549, so N stays within 0..9.
inline int companion_port(int instance) {
  return 14540 + instance;
}
// PX4: the onboard link's own port (it binds it and sends from it).
inline int px4_onboard_port(int instance) {
  return 14580 + instance;
}
// PX4: the ground-station link; it answers whoever writes to it.
inline int px4_gcs_port(int instance) {
  return 18570 + instance;
}
// The simulator's side when COVER is the firmware's physics: PX4's simulator_mavlink
// connects to TCP 4560 + N (firmware_link::Px4HilLink serves it); ArduCopter's JSON backend
// sends its servo packets to UDP 9002 + 10 N (firmware_link::ArduPilotJsonLink binds it).
inline int physics_port(Autopilot autopilot, int instance) {
  return autopilot == Autopilot::Px4 ? 4560 + instance : 9002 + 10 * instance;
}
// ArduCopter: SERIAL0, a TCP server (a ground station's port).
inline int arducopter_gcs_port(int instance) {
  return 5760 + 10 * instance;
}

struct PortUse {
  bool tcp = false;
  int port = 0;
};

// Every port instance N of `firmware` binds, and the companion port (which the test's own
// relay binds) and, for ArduCopter, its JSON physics port (which ArduPilotJsonLink
// binds): all must be free before it starts.
std::vector<PortUse> ports_of(Autopilot firmware, int instance);

}  // namespace cover::firmware
