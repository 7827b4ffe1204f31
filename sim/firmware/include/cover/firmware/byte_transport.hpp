#pragma once
// A byte pipe to one of a firmware's MAVLink ports on this host, for the test's own
// connection to it (FirmwareMonitor). services/mavlink has the bridge's links (UDP, serial);
// a ground station's port on ArduPilot SITL is a TCP server, so the test has this one.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace cover::firmware {

class ByteTransport {
 public:
  virtual ~ByteTransport() = default;
  // Writes all of it; false when it could not (not connected yet).
  virtual bool send(const std::uint8_t* data, std::size_t size) = 0;
  // Waits up to `timeout` for bytes; how many were read (0: none in time, or not connected:
  // a TCP transport then tries to connect again).
  virtual std::size_t receive(std::uint8_t* buffer, std::size_t capacity,
                              std::chrono::milliseconds timeout) = 0;
};

// A UDP socket on an ephemeral loopback port that sends to 127.0.0.1:`peer_port` (PX4's
// ground-station link answers whoever writes to it).
std::unique_ptr<ByteTransport> udp_transport(int peer_port);

// A TCP client of 127.0.0.1:`port`, connecting (and reconnecting) while the server is not
// up yet: the firmware opens its port some time after it starts.
std::unique_ptr<ByteTransport> tcp_transport(int port);

}  // namespace cover::firmware
