#include "cover/mavlink/link.hpp"

#include "cover/mavlink/tcp_server_link.hpp"
#include "link_factories.hpp"

namespace cover::mavlink {

std::unique_ptr<Link> make_link(const ConnectionUrl& url) {
  switch (url.kind) {
    case ConnectionUrl::Kind::UdpIn:
      return detail::make_udp(detail::UdpPeerMode::LearnFromSender, {url.host, url.port, "", 0},
                              url.to_string());
    case ConnectionUrl::Kind::UdpOut:
      return detail::make_udp(detail::UdpPeerMode::Connected, {"", 0, url.host, url.port},
                              url.to_string());
    case ConnectionUrl::Kind::Serial:
      return detail::make_serial(url.device, url.baud);
    case ConnectionUrl::Kind::TcpIn:
      return make_tcp_server_link(url.host, url.port);
    case ConnectionUrl::Kind::TcpOut:
      return detail::make_tcp_client(url.host, url.port);
  }
  return nullptr;
}

std::unique_ptr<Link> make_udp_link(const std::string& bind_host, std::uint16_t bind_port,
                                    const std::string& peer_host, std::uint16_t peer_port) {
  const std::string description = "udp://" + bind_host + ":" + std::to_string(bind_port) + " -> " +
                                  peer_host + ":" + std::to_string(peer_port);
  return detail::make_udp(detail::UdpPeerMode::Fixed, {bind_host, bind_port, peer_host, peer_port},
                          description);
}

}  // namespace cover::mavlink
