#pragma once
// Waiting in a test for something to happen (a process to reach a state, a file to appear,
// a sample to arrive): the condition is polled until it holds or a deadline passes,
// stretched by COVER_TEST_TIME_SCALE (time_scale.hpp). A test never sleeps and hopes.
#include <chrono>
#include <functional>
#include <thread>

#include "cover/test/time_scale.hpp"

namespace cover::test {

// Polls `condition` every `poll` until it holds (true) or scaled(timeout) passes (false,
// after one last look).
inline bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout,
                       std::chrono::milliseconds poll = std::chrono::milliseconds(5)) {
  const auto deadline = std::chrono::steady_clock::now() + scaled(timeout);
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= deadline) return condition();
    std::this_thread::sleep_for(poll);  // polling a condition with a deadline
  }
  return true;
}

}  // namespace cover::test
