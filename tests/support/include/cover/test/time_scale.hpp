#pragma once
// Wall-clock deadlines of the tests, stretched by COVER_TEST_TIME_SCALE for a slow or
// loaded machine (scripts/test --sanitize sets 3). Every deadline a test waits on goes
// through scaled() (wait_until.hpp waits on a condition with one): a deadline is how long a
// test is willing to wait for something that should happen, never a measurement, so
// stretching it cannot hide a failure.
#include <chrono>
#include <cmath>
#include <cstdlib>

namespace cover::test {

// COVER_TEST_TIME_SCALE, default 1; a value below 1 or not a number reads as 1.
inline double time_scale() {
  const char* text = std::getenv("COVER_TEST_TIME_SCALE");
  const double scale = text != nullptr ? std::atof(text) : 1.0;
  return scale >= 1.0 ? scale : 1.0;
}

// The scale rounded up, for deadlines counted in whole units (seconds, loop passes).
inline int whole_time_scale() {
  return static_cast<int>(std::ceil(time_scale()));
}

inline std::chrono::milliseconds scaled(std::chrono::milliseconds deadline) {
  return std::chrono::milliseconds(
      static_cast<long long>(static_cast<double>(deadline.count()) * time_scale()));
}

}  // namespace cover::test
