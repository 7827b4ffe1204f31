#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "cover/mavlink/link.hpp"

namespace cover::mavlink {

// tcpin://IP:PORT: a listening TCP socket that talks to one client, the one that connected
// last (a peer that reconnects after a drop replaces its dead connection; PX4 SITL's
// simulator_mavlink is such a client, connecting to 4560 + instance until it succeeds).
// read() accepts a waiting client and then reads from it; a client that hangs up or fails is
// dropped and the next one accepted, the listening socket stays open. write() sends the whole
// frame to the client (false when there is none).
class TcpServerLink : public Link {
 public:
  // Clients accepted since open(); a new value means a new connection (reset the parser).
  virtual std::uint64_t clients_accepted() const = 0;
  virtual bool has_client() const = 0;
  // The port bound (the kernel's pick for port 0), 0 while closed.
  virtual std::uint16_t local_port() const = 0;
};

std::unique_ptr<TcpServerLink> make_tcp_server_link(const std::string& bind_host,
                                                    std::uint16_t port);

}  // namespace cover::mavlink
