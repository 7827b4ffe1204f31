#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>

#include "cover/vocabulary/stamp.hpp"

namespace cover::clock {

// Nanoseconds of the host's monotonic clock. Stamps on the wire use the system clock
// (below) so that processes agree; durations and timeouts use this one.
std::int64_t monotonic_ns();

// Nanoseconds since the Unix epoch (CLOCK_REALTIME): the stamp written on every sample.
// Plus the test-only offset below, when one is set.
std::int64_t system_ns();

// TEST ONLY: the environment variable COVER_TEST_CLOCK_OFFSET_MS (milliseconds, may be
// negative or fractional), read once at the first system_ns(), shifts this process's
// system clock, so that tests can play a host whose clock is off (docs/time.md). Logged
// as a warning when set; never set it on a vehicle.
inline constexpr const char* kTestClockOffsetEnv = "COVER_TEST_CLOCK_OFFSET_MS";
// The offset system_ns() adds, ns (0 unless the test setting is given).
std::int64_t test_clock_offset_ns();

// Seconds <-> nanoseconds: ns_to_s, s_to_ns (cover/vocabulary/stamp.hpp).

// The system clock in seconds since the Unix epoch (records, heartbeats of the ground side).
inline double system_s() {
  return ns_to_s(system_ns());
}

// A timeout given in seconds (parameters are) as the milliseconds the std waits take.
inline std::chrono::milliseconds to_milliseconds(double seconds) {
  return std::chrono::milliseconds(static_cast<long>(seconds * 1000.0));
}

}  // namespace cover::clock
