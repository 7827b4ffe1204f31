#include "cover/clock/clock.hpp"

#include <time.h>

namespace cover::clock {

namespace {
std::int64_t read(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}
}  // namespace

std::int64_t monotonic_ns() { return read(CLOCK_MONOTONIC); }
std::int64_t system_ns() { return read(CLOCK_REALTIME); }

}  // namespace cover::clock
