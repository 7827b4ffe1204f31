#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "cover/mavlink/link.hpp"

namespace cover::mavlink::detail {

// The concrete links behind make_link / make_udp_link.
enum class UdpPeerMode {
  LearnFromSender,  // udpin: answer whoever sent last
  Connected,        // udpout: connect() to the peer, hear only it
  Fixed,            // SITL style: send to a fixed peer, hear anyone on the bound port
};

struct UdpEndpoints {
  std::string bind_host;  // empty: do not bind (the kernel picks an ephemeral port)
  std::uint16_t bind_port = 0;
  std::string peer_host;  // empty with LearnFromSender
  std::uint16_t peer_port = 0;
};

std::unique_ptr<Link> make_udp(UdpPeerMode mode, UdpEndpoints endpoints, std::string description);
std::unique_ptr<Link> make_serial(std::string device, int baud);
// tcp://HOST:PORT: connects on open(); a dropped connection closes the link, and the
// owner's next open() connects again.
std::unique_ptr<Link> make_tcp_client(std::string host, std::uint16_t port);

}  // namespace cover::mavlink::detail
