#include "cover/clock/clock.hpp"

#include <spdlog/spdlog.h>
#include <time.h>

#include <cerrno>
#include <cstdlib>

namespace cover::clock {

namespace {
std::int64_t read(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

// A day: anything larger is a typo, not a clock a test means to play.
constexpr double kMaxTestOffsetMs = 86'400'000.0;

std::int64_t read_test_offset_ns() {
  const char* text = std::getenv(kTestClockOffsetEnv);
  if (!text || *text == '\0') return 0;
  char* end = nullptr;
  errno = 0;
  const double ms = std::strtod(text, &end);
  if (errno != 0 || end == text || *end != '\0' || !std::isfinite(ms) ||
      std::abs(ms) > kMaxTestOffsetMs) {
    spdlog::error("{}='{}' is not a number of milliseconds (|x| <= {:.0f}): ignored",
                  kTestClockOffsetEnv, text, kMaxTestOffsetMs);
    return 0;
  }
  spdlog::warn(
      "TEST ONLY: {}={} shifts this process's system clock by {:+.3f} ms: its stamps and its "
      "clock answers (cover/time/reply) are off by that much. Never set this on a vehicle.",
      kTestClockOffsetEnv, text, ms);
  return std::llround(ms * 1e6);
}
}  // namespace

std::int64_t test_clock_offset_ns() {
  static const std::int64_t offset_ns = read_test_offset_ns();
  return offset_ns;
}

std::int64_t monotonic_ns() {
  return read(CLOCK_MONOTONIC);
}
std::int64_t system_ns() {
  return read(CLOCK_REALTIME) + test_clock_offset_ns();
}

}  // namespace cover::clock
