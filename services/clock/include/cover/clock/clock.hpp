#pragma once

#include <cstdint>

namespace cover::clock {

// Nanoseconds of the host's monotonic clock. Stamps on the wire use the system clock
// (below) so that processes agree; durations and timeouts use this one.
std::int64_t monotonic_ns();

// Nanoseconds since the Unix epoch (CLOCK_REALTIME): the stamp written on every sample.
std::int64_t system_ns();

inline double ns_to_s(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }
inline std::int64_t s_to_ns(double s) { return static_cast<std::int64_t>(s * 1e9); }

}  // namespace cover::clock
