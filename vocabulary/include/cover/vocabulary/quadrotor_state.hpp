#pragma once

#include <type_traits>

#include "cover/vocabulary/pod_types.hpp"

namespace cover::sim {

// The controller's input u = [F, wx, wy, wz] (docs/model.md): F collective thrust per unit
// NOMINAL mass (m/s^2), w body rates (FLU, rad/s).
struct QuadrotorCommand {
  double thrust_m_s2 = 0.0;
  Vec3 body_rate_rad_s;
};

// World-frame rigid-body state (ENU, FLU body). Plain data: part of WorldState.
struct QuadrotorState {
  Vec3 position_m;
  Vec3 velocity_m_s;
  Quat attitude;          // body -> world
  Vec3 body_rate_rad_s;   // the rate loop's actual output
  double thrust_n = 0.0;  // actual collective thrust after the motor lag
};

static_assert(std::is_trivially_copyable_v<QuadrotorCommand>);
static_assert(std::is_trivially_copyable_v<QuadrotorState>);

}  // namespace cover::sim
