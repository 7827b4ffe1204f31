#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cover/time_sync/offset_filter.hpp"

namespace cover::time_sync {

struct PeerOffset {
  std::string peer;  // host/process
  OffsetEstimate estimate;
};

// The offsets to every peer we exchange with, each through its own OffsetFilter. A peer
// that restarts (a new session) starts a new filter: its clock may be another one now. A
// peer silent for `forget_after_ns` is forgotten (it sends nothing we could misjudge).
class PeerOffsets {
 public:
  PeerOffsets(std::size_t window, std::int64_t forget_after_ns);

  // False when the sample starts a new filter (a peer or session not seen before).
  bool add(const std::string& peer, std::uint64_t session, const OffsetSample& sample);
  // Forgets peers silent at `now_ns`; returns their names.
  std::vector<std::string> forget_silent(std::int64_t now_ns);
  // Forgets the peers `keep` says no to (no longer asked); returns their names.
  template <typename Keep>
  std::vector<std::string> forget_unless(Keep keep) {
    std::vector<std::string> gone;
    for (auto it = peers_.begin(); it != peers_.end();) {
      if (keep(it->first)) {
        ++it;
      } else {
        gone.push_back(it->first);
        it = peers_.erase(it);
      }
    }
    return gone;
  }

  // Every known peer's estimate at `now_ns`, by name.
  std::vector<PeerOffset> all(std::int64_t now_ns) const;
  // The peer with the largest |offset|; nullopt when none is known.
  std::optional<PeerOffset> largest(std::int64_t now_ns) const;

 private:
  struct Peer {
    std::uint64_t session = 0;
    OffsetFilter filter;
    std::int64_t heard_ns = 0;
  };
  std::size_t window_;
  std::int64_t forget_after_ns_;
  std::map<std::string, Peer> peers_;
};

// "clock offset from <self> to <peer> is 52.3 ms (its clock ahead; limit 20 ms)" when
// |offset| exceeds `limit_ms`; nullopt otherwise.
std::optional<std::string> offset_limit_reason(const std::string& self, const PeerOffset& peer,
                                               double limit_ms);

// Milliseconds of a nanosecond count, for reports.
inline double ns_to_ms(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-6;
}

}  // namespace cover::time_sync
