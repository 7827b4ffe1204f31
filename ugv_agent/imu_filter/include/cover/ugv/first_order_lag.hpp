#pragma once

#include <cmath>

#include "cover/vocabulary/angles.hpp"

namespace cover::ugv {

// The time constant of a first-order low-pass with cut-off `cutoff_hz`.
inline double lag_time_constant_s(double cutoff_hz) {
  return 1.0 / (model::kTwoPi * cutoff_hz);
}

// Exact step response weight of a first-order lag over dt (alpha = 1 - exp(-dt / tau)):
// correct for any dt > 0, so jittery sample times do not change the cut-off.
inline double lag_blend_weight(double dt_s, double tau_s) {
  return 1.0 - std::exp(-dt_s / tau_s);
}

}  // namespace cover::ugv
