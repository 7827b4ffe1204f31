#include "sensor_latency.hpp"

#include <algorithm>

namespace cover::sim {

SensorLatency::SensorLatency(std::int64_t key_step)
    : key_step_(std::max<std::int64_t>(key_step, 1)) {
  samples_ms_.reserve(kReservedSamples);
}

SensorLatency::Slot& SensorLatency::slot_of(std::int64_t key) {
  // Keys at least key_step apart: the 256 most recent do not share a slot.
  return slots_[static_cast<std::size_t>(key / key_step_) % slots_.size()];
}

void SensorLatency::published(std::int64_t key, std::int64_t now_ns) {
  if (key <= 0) return;
  slot_of(key) = Slot{key, now_ns, {}};
}

bool SensorLatency::answered(int uav, std::int64_t key, std::int64_t now_ns) {
  if (uav < 0 || uav >= fleet::kMaxUavs || key <= 0) return false;
  Slot& slot = slot_of(key);
  bool& answered = slot.answered[static_cast<std::size_t>(uav)];
  if (slot.key != key || answered) return false;
  answered = true;
  samples_ms_.push_back(static_cast<double>(now_ns - slot.published_ns) * 1e-6);
  return true;
}

}  // namespace cover::sim
