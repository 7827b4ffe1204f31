#include "cover/time_sync/exchange.hpp"

namespace cover::time_sync {

namespace {
// a - b, or nullopt when it does not fit (times from outside may be anything).
std::optional<std::int64_t> minus(std::int64_t a, std::int64_t b) {
  std::int64_t out = 0;
  if (__builtin_sub_overflow(a, b, &out)) return std::nullopt;
  return out;
}
}  // namespace

std::optional<OffsetSample> measure(const Exchange& e) {
  const auto outbound = minus(e.t2_ns, e.t1_ns);  // network + offset
  const auto inbound = minus(e.t3_ns, e.t4_ns);   // offset - network
  const auto round_trip = minus(e.t4_ns, e.t1_ns);
  const auto held = minus(e.t3_ns, e.t2_ns);
  if (!outbound || !inbound || !round_trip || !held) return std::nullopt;
  if (*round_trip < 0 || *held < 0) return std::nullopt;
  const auto delay = minus(*round_trip, *held);
  std::int64_t sum = 0;
  if (!delay || *delay < 0 || __builtin_add_overflow(*outbound, *inbound, &sum)) {
    return std::nullopt;
  }
  return OffsetSample{sum / 2, *delay, e.t4_ns};
}

}  // namespace cover::time_sync
