#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <utility>

namespace cover::mocap {

// Maps the server's capture times to our clock.
//  server: the same clock (the simulator's time; or hosts kept together by chrony).
//  offset: ours = server + offset, offset = the smallest (arrival - server) seen over the
//          last window: a frame cannot arrive before it was captured, so that minimum is the
//          clock offset plus the smallest transport delay (loopback ~0.05 ms, a LAN
//          ~0.2 ms). A stamp is then late by at most that delay; the window lets the offset
//          follow a drifting server clock.
class ServerClock {
 public:
  ServerClock(const std::string& time_source, double window_s);
  // `arrival_ns`: our clock when the frame's first message came.
  std::int64_t to_ours(std::int64_t server_ns, std::int64_t arrival_ns);
  std::int64_t offset_ns() const { return offset_ns_; }
  bool identity() const { return identity_; }

 private:
  bool identity_;
  std::int64_t window_ns_;
  std::int64_t offset_ns_ = 0;
  std::deque<std::pair<std::int64_t, std::int64_t>> minima_;  // (arrival, delta), increasing delta
};

}  // namespace cover::mocap
