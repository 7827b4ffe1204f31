#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cover/vocabulary/autopilot.hpp"

namespace cover::sim::fc {

// The simulator imitates one cover::Autopilot: its HEARTBEAT, custom modes, ACK results and
// failsafe follow that one's rules (docs/autopilots.md). The flight modes it has, by what
// they do:
//  Hold     PX4 AUTO.LOITER / ArduPilot BRAKE: PX4's mode after boot (without RC it starts
//           in Hold), levelled, height held;
//  Manual   PX4 MANUAL / ArduPilot STABILIZE: ArduPilot's mode after boot (sticks centred:
//           levelled, height held, as Position: the simulator has no sticks);
//  Position PX4 POSCTL / ArduPilot LOITER: the safety pilot's switch, levelled, height held;
//  Offboard PX4 OFFBOARD / ArduPilot GUIDED_NOGPS: the companion's body-rate setpoints;
//  Land     PX4 AUTO.LAND / ArduPilot LAND: levelled descent; ArduPilot disarms on
//           touchdown, PX4 COM_DISARM_LAND after it.
enum class FlightMode { Hold, Manual, Position, Offboard, Land };

// The mode each autopilot boots in (PX4 SITL: AUTO.LOITER; ArduCopter: STABILIZE).
FlightMode start_mode(Autopilot profile);

// The autopilot's own name of the mode ("OFFBOARD", "GUIDED_NOGPS", ...).
const char* mode_name(Autopilot profile, FlightMode mode);
// HEARTBEAT.custom_mode: PX4 main mode in bits 16-23 and sub mode in 24-31; ArduPilot the
// mode number.
std::uint32_t custom_mode(Autopilot profile, FlightMode mode);
// The mode a DO_SET_MODE asks for (param1 custom-mode flag, param2 main mode / mode
// number, param3 PX4 sub mode); nullopt for a mode the simulator does not have.
std::optional<FlightMode> requested_mode(Autopilot profile, float param1, float param2,
                                         float param3);
// A mode named as either autopilot names it (case-insensitive): AUTO.LOITER, BRAKE, MANUAL,
// STABILIZE, POSCTL, LOITER, OFFBOARD, GUIDED_NOGPS, LAND, AUTO.LAND. For fault injection
// flags.
std::optional<FlightMode> parse_mode_name(const std::string& text);

}  // namespace cover::sim::fc
