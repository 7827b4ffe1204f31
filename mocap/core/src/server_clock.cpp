#include "cover/mocap/server_clock.hpp"

#include <cmath>

namespace cover::mocap {

ServerClock::ServerClock(const std::string& time_source, double window_s)
    : identity_(time_source == "server"), window_ns_(std::llround(window_s * 1e9)) {}

std::int64_t ServerClock::to_ours(std::int64_t server_ns, std::int64_t arrival_ns) {
  if (identity_) return server_ns;
  const std::int64_t delta = arrival_ns - server_ns;
  // A monotone queue: the window's minimum at the front, bounded by the frames in a window.
  while (!minima_.empty() && minima_.back().second >= delta) minima_.pop_back();
  minima_.emplace_back(arrival_ns, delta);
  while (minima_.front().first < arrival_ns - window_ns_) minima_.pop_front();
  offset_ns_ = minima_.front().second;
  return server_ns + offset_ns_;
}

}  // namespace cover::mocap
