#include "sensor_latency.hpp"

namespace cover::sim {

SensorLatency::Slot& SensorLatency::slot_of(std::int64_t stamp_ns) {
  // Stamps are whole control periods (>= 1 ms apart): by the millisecond, recent stamps
  // do not share a slot.
  return slots_[static_cast<std::size_t>(stamp_ns / 1'000'000) % slots_.size()];
}

void SensorLatency::published(std::int64_t stamp_ns, std::int64_t now_ns) {
  if (stamp_ns < 0) return;
  slot_of(stamp_ns) = Slot{stamp_ns, now_ns, {}};
}

bool SensorLatency::answered(int uav, std::int64_t stamp_ns, std::int64_t now_ns) {
  if (uav < 0 || uav >= fleet::kMaxUavs || stamp_ns <= 0) return false;
  Slot& slot = slot_of(stamp_ns);
  bool& answered = slot.answered[static_cast<std::size_t>(uav)];
  if (slot.stamp_ns != stamp_ns || answered) return false;
  answered = true;
  samples_ms_.push_back(static_cast<double>(now_ns - slot.published_ns) * 1e-6);
  return true;
}

}  // namespace cover::sim
