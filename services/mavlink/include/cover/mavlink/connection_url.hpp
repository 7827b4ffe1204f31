#pragma once

#include <cstdint>
#include <string>

namespace cover::mavlink {

// A MAVLink connection as MAVSDK writes it:
//   udpin://IP:PORT          listen on IP:PORT, answer whoever sent last
//   udpout://HOST:PORT       send to HOST:PORT (from an ephemeral port), read the replies
//   serial:///dev/ttyX:BAUD  a serial port (termios, 8N1, raw, no flow control)
struct ConnectionUrl {
  enum class Kind { UdpIn, UdpOut, Serial };
  Kind kind = Kind::UdpIn;
  std::string host;  // UdpIn: the address to bind; UdpOut: the peer's
  std::uint16_t port = 0;
  std::string device;  // Serial
  int baud = 57600;    // Serial: one of the termios speeds (9600 .. 3000000)

  // Throws std::invalid_argument naming what is wrong and the accepted forms.
  static ConnectionUrl parse(const std::string& text);
  std::string to_string() const;
};

}  // namespace cover::mavlink
