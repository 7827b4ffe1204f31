#pragma once

#include "cover/sim/quadrotor.hpp"
#include "cover/sim/world.hpp"

namespace cover::sim::fc {

// What a flight controller flies without a companion: the attitude levelled (body rates
// against the tilt) and a vertical speed tracked around the hover thrust it has learned
// (the plant's true one). Used by the direct path's offboard-loss descent and by the
// simulated autopilot's land and hold modes.
QuadrotorCommand levelled_vertical_speed_command(const World& world, double vertical_speed_m_s);

// Levelled, holding the height `hold_height_m` (world z): a vertical speed toward it,
// bounded (the safety pilot's position / loiter mode with the sticks centred).
QuadrotorCommand levelled_height_hold_command(const World& world, double hold_height_m);

}  // namespace cover::sim::fc
