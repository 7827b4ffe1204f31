#pragma once

#include <cmath>
#include <cstdint>

namespace cover::clock {

// Stamps are integer nanoseconds on the wire and seconds (double) in the libraries.
// Every conversion between the two goes through these, so that a time made from whole
// nanoseconds (the simulator's) survives s -> ns -> s bit for bit: a lockstep run across
// processes then computes exactly what the in-process one does.
inline double ns_to_s(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-9;
}
// Rounded to the nearest nanosecond (truncating would read 0.01 s as 9999999 ns).
inline std::int64_t s_to_ns(double s) {
  return std::llround(s * 1e9);
}

}  // namespace cover::clock
