#include "cover/time_sync/peer_offsets.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace cover::time_sync {

PeerOffsets::PeerOffsets(std::size_t window, std::int64_t forget_after_ns)
    : window_(window), forget_after_ns_(forget_after_ns) {}

bool PeerOffsets::add(const std::string& peer, std::uint64_t session, const OffsetSample& sample) {
  auto found = peers_.find(peer);
  bool known = true;
  if (found == peers_.end()) {
    found = peers_.emplace(peer, Peer{session, OffsetFilter(window_), 0}).first;
    known = false;
  } else if (found->second.session != session) {
    found->second.session = session;
    found->second.filter.clear();
    known = false;
  }
  found->second.filter.add(sample);
  found->second.heard_ns = sample.received_ns;
  return known;
}

std::vector<std::string> PeerOffsets::forget_silent(std::int64_t now_ns) {
  std::vector<std::string> gone;
  for (auto it = peers_.begin(); it != peers_.end();) {
    if (now_ns - it->second.heard_ns > forget_after_ns_) {
      gone.push_back(it->first);
      it = peers_.erase(it);
    } else {
      ++it;
    }
  }
  return gone;
}

std::vector<PeerOffset> PeerOffsets::all(std::int64_t now_ns) const {
  std::vector<PeerOffset> out;
  for (const auto& [name, peer] : peers_) {
    if (const auto e = peer.filter.estimate(now_ns)) out.push_back({name, *e});
  }
  return out;
}

std::optional<PeerOffset> PeerOffsets::largest(std::int64_t now_ns) const {
  std::optional<PeerOffset> worst;
  for (PeerOffset& p : all(now_ns)) {
    if (!worst || std::llabs(p.estimate.offset_ns) > std::llabs(worst->estimate.offset_ns)) {
      worst = std::move(p);
    }
  }
  return worst;
}

std::optional<std::string> offset_limit_reason(const std::string& self, const PeerOffset& peer,
                                               double limit_ms) {
  const double offset_ms = ns_to_ms(peer.estimate.offset_ns);
  if (!(std::abs(offset_ms) > limit_ms)) return std::nullopt;
  char numbers[96];
  std::snprintf(numbers, sizeof numbers, " is %.1f ms (its clock %s; limit %g ms)",
                std::abs(offset_ms), offset_ms > 0 ? "ahead" : "behind", limit_ms);
  return "clock offset from " + self + " to " + peer.peer + numbers;
}

}  // namespace cover::time_sync
