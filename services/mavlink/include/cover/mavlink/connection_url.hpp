#pragma once

#include <cstdint>
#include <string>

namespace cover::mavlink {

// A MAVLink connection as MAVSDK writes it:
//   udpin://IP:PORT          listen on IP:PORT, answer whoever sent last
//   udpout://HOST:PORT       send to HOST:PORT (from an ephemeral port), read the replies
//   serial:///dev/ttyX:BAUD  a serial port (termios, 8N1, raw, no flow control)
//   tcpin://IP:PORT          listen on IP:PORT, talk to the client that connected last
//                            (PX4 SITL's simulator_mavlink connects to 4560 + instance)
//   tcp://HOST:PORT          connect to HOST:PORT (tcpout:// is the same)
struct ConnectionUrl {
  enum class Kind { UdpIn, UdpOut, Serial, TcpIn, TcpOut };
  Kind kind = Kind::UdpIn;
  std::string host;  // UdpIn / TcpIn: the address to bind; UdpOut / TcpOut: the peer's
  std::uint16_t port = 0;
  std::string device;  // Serial
  int baud = 57600;    // Serial: one of the termios speeds (9600 .. 3000000)

  // Throws std::invalid_argument naming what is wrong and the accepted forms.
  static ConnectionUrl parse(const std::string& text);
  std::string to_string() const;
};

}  // namespace cover::mavlink
