#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cover/fleet/fleet_size.hpp"

namespace cover::sim {

// The realtime sensor-to-command latency of the direct path: from writing a relative state
// (its stamp) to taking the first command of each UAV that names that stamp. Later
// commands naming the same stamp are an agent stepping again on inputs it already had
// (with no new state, every 1.5 periods): counted, they were the run's end (15, 30, 45 ms),
// not the path. Remembers the last 256 stamps (2.56 s at 100 Hz); not thread-safe.
class SensorLatency {
 public:
  SensorLatency() { samples_ms_.reserve(kReservedSamples); }
  void published(std::int64_t stamp_ns, std::int64_t now_ns);
  // The command of `uav` (0..kMaxUavs-1) names `stamp_ns`: a sample if it is the first of
  // that UAV to name a stamp still remembered; false otherwise (or for a bad uav / stamp).
  bool answered(int uav, std::int64_t stamp_ns, std::int64_t now_ns);
  const std::vector<double>& samples_ms() const { return samples_ms_; }

 private:
  static constexpr std::size_t kReservedSamples = 1 << 16;
  struct Slot {
    std::int64_t stamp_ns = -1;
    std::int64_t published_ns = 0;
    std::array<bool, fleet::kMaxUavs> answered{};
  };
  Slot& slot_of(std::int64_t stamp_ns);

  std::array<Slot, 256> slots_{};
  std::vector<double> samples_ms_;
};

}  // namespace cover::sim
