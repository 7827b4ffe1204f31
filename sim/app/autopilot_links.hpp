#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/parser.hpp"

namespace cover::sim {

// UDP ports of a set of simulated autopilots, as PX4 SITL numbers them: vehicle i binds
// 127.0.0.1:(bind_port_base + i) and sends to 127.0.0.1:(peer_port_base + i).
struct MavlinkPorts {
  std::uint16_t bind_port_base = 0;
  std::uint16_t peer_port_base = 0;
};

// The simulated UAV autopilots' MAVLink links: one UDP socket per UAV and a thread reading
// it, which hands every frame to `on_frame` (the caller serialises with its own lock).
// Sending is the caller's, under that same lock.
class AutopilotLinks {
 public:
  using FrameHandler = std::function<void(int uav, const mavlink::Frame& frame)>;

  // Opens every link; throws std::runtime_error naming a port that cannot be bound.
  AutopilotLinks(int uav_count, MavlinkPorts ports, FrameHandler on_frame);
  ~AutopilotLinks();
  AutopilotLinks(const AutopilotLinks&) = delete;
  AutopilotLinks& operator=(const AutopilotLinks&) = delete;

  void send(int uav, const mavlink::EncodedFrame& frame);
  void send(int uav, const std::vector<mavlink::EncodedFrame>& frames);
  // Ends the reader threads: no frame is handed over after this returns.
  void stop();

  std::string describe(int uav) const;
  // Only after stop(): what UAV `uav`'s parser saw, and the datagrams that could not be sent.
  const mavlink::ParserStats& stats(int uav) const { return channels_[uav]->parser.stats(); }
  std::uint64_t send_failures(int uav) const { return channels_[uav]->send_failures; }

 private:
  struct Channel {
    std::unique_ptr<mavlink::Link> link;
    mavlink::StreamParser parser;
    std::uint64_t send_failures = 0;
    std::thread reader;
  };
  void read_loop(int uav);

  FrameHandler on_frame_;
  std::vector<std::unique_ptr<Channel>> channels_;
  std::atomic<bool> stop_{false};
};

// Opens a fixed-peer UDP link on loopback or throws std::runtime_error naming the port.
std::unique_ptr<mavlink::Link> open_sitl_link(std::uint16_t bind_port, std::uint16_t peer_port);

}  // namespace cover::sim
