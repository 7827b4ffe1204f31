#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

#include "cover/time_sync/exchange.hpp"

namespace cover::time_sync {

// The offset to one peer as we currently believe it.
struct OffsetEstimate {
  std::int64_t offset_ns = 0;  // peer's clock minus ours
  std::int64_t delay_ns = 0;   // round trip of the sample it comes from
  // The offset is within +-uncertainty_ns of the truth (the network's asymmetry can be
  // at most the whole round trip): delay / 2.
  std::int64_t uncertainty_ns = 0;
  std::int64_t age_ns = 0;  // since that sample was measured
};

// NTP's clock filter (RFC 5905 sec. 10): of the last `window` samples, the one with the
// least delay. A sample delayed by a busy network or a loaded host has a larger delay and
// an offset wrong by up to half of it; the quickest exchange is the most trustworthy.
class OffsetFilter {
 public:
  explicit OffsetFilter(std::size_t window = 8);

  void add(const OffsetSample& sample);
  void clear() { samples_.clear(); }
  std::size_t size() const { return samples_.size(); }

  // The least-delay sample of the window, aged at `now_ns` (our clock); nullopt when empty.
  std::optional<OffsetEstimate> estimate(std::int64_t now_ns) const;

 private:
  std::size_t window_;
  std::deque<OffsetSample> samples_;
};

}  // namespace cover::time_sync
