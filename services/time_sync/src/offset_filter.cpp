#include "cover/time_sync/offset_filter.hpp"

#include <algorithm>

namespace cover::time_sync {

OffsetFilter::OffsetFilter(std::size_t window) : window_(std::max<std::size_t>(window, 1)) {}

void OffsetFilter::add(const OffsetSample& sample) {
  samples_.push_back(sample);
  while (samples_.size() > window_) samples_.pop_front();
}

std::optional<OffsetEstimate> OffsetFilter::estimate(std::int64_t now_ns) const {
  if (samples_.empty()) return std::nullopt;
  // Ties go to the newer sample: the same quality, a fresher clock reading.
  const OffsetSample* best = &samples_.front();
  for (const OffsetSample& s : samples_) {
    if (s.delay_ns <= best->delay_ns) best = &s;
  }
  OffsetEstimate e;
  e.offset_ns = best->offset_ns;
  e.delay_ns = best->delay_ns;
  e.uncertainty_ns = best->delay_ns / 2;
  e.age_ns = std::max<std::int64_t>(0, now_ns - best->received_ns);
  return e;
}

}  // namespace cover::time_sync
