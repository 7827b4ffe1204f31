#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <iterator>

namespace cover::shm::test {

// 64 KiB where every element holds the same counter: a torn copy has two different ones.
struct CounterPayload {
  std::uint64_t values[8192];
};
static_assert(sizeof(CounterPayload) == 64 * 1024);

inline void fill(CounterPayload& payload, std::uint64_t counter) {
  std::fill(std::begin(payload.values), std::end(payload.values), counter);
}

inline bool uniform(const CounterPayload& payload) {
  return std::all_of(std::begin(payload.values), std::end(payload.values),
                     [&](std::uint64_t v) { return v == payload.values[0]; });
}

inline constexpr std::uint32_t kCounterLayout = 7;

// Stands in for the simulator's step between two writes. A writer that does nothing but
// write starves seqlock readers (each copy overlaps the next write). Busy, not a sleep:
// it synchronises nothing, and a sleep on a loaded host lasts milliseconds.
inline void work_between_writes() {
  const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(20);
  while (std::chrono::steady_clock::now() < until) {
  }
}

}  // namespace cover::shm::test
