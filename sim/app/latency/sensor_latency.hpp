#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cover/vocabulary/fleet_size.hpp"

namespace cover::sim {

// The realtime sensor-to-command latency: from writing a tick's relative states to taking
// the first answer of each UAV that names them. The direct path names them by their stamp
// (a command's measurement stamp), the path through an autopilot by the tick (a setpoint's
// time_boot_ms). Later answers naming the same key are an agent stepping again on inputs
// it already had (with no new state, every 1.5 periods): counted, they were the run's end
// (15, 30, 45 ms), not the path. Remembers the last 256 keys (2.56 s at 100 Hz); not
// thread-safe.
class SensorLatency {
 public:
  // Keys are positive and published at least `key_step` apart: stamps in ns are whole
  // control periods (key_step 1 ms), ticks are counted (key_step 1).
  static constexpr std::int64_t kStampKeyStep = 1'000'000;
  static constexpr std::int64_t kTickKeyStep = 1;
  explicit SensorLatency(std::int64_t key_step);
  void published(std::int64_t key, std::int64_t now_ns);
  // The answer of `uav` (0..kMaxUavs-1) names `key`: a sample if it is the first of that
  // UAV to name a key still remembered; false otherwise (or for a bad uav / key).
  bool answered(int uav, std::int64_t key, std::int64_t now_ns);
  const std::vector<double>& samples_ms() const { return samples_ms_; }

 private:
  static constexpr std::size_t kReservedSamples = 1 << 16;
  struct Slot {
    std::int64_t key = -1;
    std::int64_t published_ns = 0;
    std::array<bool, fleet::kMaxUavs> answered{};
  };
  Slot& slot_of(std::int64_t key);

  std::int64_t key_step_;
  std::array<Slot, 256> slots_{};
  std::vector<double> samples_ms_;
};

}  // namespace cover::sim
