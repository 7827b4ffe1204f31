#pragma once

#include <cstdint>
#include <optional>

namespace cover::time_sync {

// One four-timestamp exchange, as NTP makes it (RFC 5905 sec. 8): the asker's clock when
// it sent the request (t1) and when the reply arrived (t4), the peer's clock when the
// request arrived (t2) and when it sent the reply (t3). Nanoseconds since the Unix epoch.
struct Exchange {
  std::int64_t t1_ns = 0;
  std::int64_t t2_ns = 0;
  std::int64_t t3_ns = 0;
  std::int64_t t4_ns = 0;
};

// What one exchange says about the peer's clock.
struct OffsetSample {
  // Peer's clock minus ours: ((t2 - t1) + (t3 - t4)) / 2. Positive: the peer is ahead.
  // Exact when the two network legs take equally long; off by at most delay / 2.
  std::int64_t offset_ns = 0;
  // Round trip spent on the network: (t4 - t1) - (t3 - t2), each difference on one clock.
  std::int64_t delay_ns = 0;
  std::int64_t received_ns = 0;  // t4: when it was measured, on our clock
};

// The sample of `e`; nullopt when its times cannot come from a real exchange (a reply
// before its request, a peer that answered before it was asked, a negative delay, or
// values so far apart that the arithmetic would overflow).
std::optional<OffsetSample> measure(const Exchange& e);

}  // namespace cover::time_sync
