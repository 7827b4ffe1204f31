#include "autopilot_links.hpp"

#include <array>
#include <chrono>
#include <stdexcept>

namespace cover::sim {

namespace {
// Bounds how long stop() waits for a reader to notice.
constexpr std::chrono::milliseconds kReadTimeout{50};
constexpr const char* kLoopback = "127.0.0.1";
}  // namespace

std::unique_ptr<mavlink::Link> open_sitl_link(std::uint16_t bind_port, std::uint16_t peer_port) {
  auto link = mavlink::make_udp_link(kLoopback, bind_port, kLoopback, peer_port);
  if (!link->open()) {
    throw std::runtime_error("MAVLink link " + link->describe() +
                             " could not open: " + link->last_error());
  }
  return link;
}

AutopilotLinks::AutopilotLinks(int uav_count, MavlinkPorts ports, FrameHandler on_frame)
    : on_frame_(std::move(on_frame)) {
  for (int u = 0; u < uav_count; ++u) {
    auto channel = std::make_unique<Channel>();
    channel->link = open_sitl_link(static_cast<std::uint16_t>(ports.bind_port_base + u),
                                   static_cast<std::uint16_t>(ports.peer_port_base + u));
    channels_.push_back(std::move(channel));
  }
  // Started once every link is open: a failed bind above leaves no thread behind.
  for (int u = 0; u < uav_count; ++u) {
    channels_[u]->reader = std::thread([this, u] { read_loop(u); });
  }
}

AutopilotLinks::~AutopilotLinks() {
  stop();
}

void AutopilotLinks::stop() {
  stop_ = true;
  for (auto& channel : channels_) {
    if (channel->reader.joinable()) channel->reader.join();
  }
}

void AutopilotLinks::read_loop(int uav) {
  Channel& channel = *channels_[uav];
  std::array<std::uint8_t, 2048> buffer{};
  while (!stop_) {
    const std::size_t n = channel.link->read(buffer.data(), buffer.size(), kReadTimeout);
    if (n == 0) {
      // A UDP socket only closes on a receive error; reopen it (same port).
      if (!channel.link->is_open() && !stop_) channel.link->open();
      continue;
    }
    channel.parser.feed(buffer.data(), n,
                        [this, uav](const mavlink::Frame& frame) { on_frame_(uav, frame); });
  }
}

void AutopilotLinks::send(int uav, const mavlink::EncodedFrame& frame) {
  Channel& channel = *channels_[uav];
  if (!channel.link->write(frame.bytes.data(), frame.size)) ++channel.send_failures;
}

void AutopilotLinks::send(int uav, const std::vector<mavlink::EncodedFrame>& frames) {
  for (const auto& frame : frames) send(uav, frame);
}

std::string AutopilotLinks::describe(int uav) const {
  return channels_[uav]->link->describe();
}

}  // namespace cover::sim
