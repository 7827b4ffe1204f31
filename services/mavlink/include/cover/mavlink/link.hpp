#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "cover/mavlink/connection_url.hpp"

namespace cover::mavlink {

// A byte link to an autopilot: a UDP socket or a serial port. Not thread-safe except
// that one thread may read while another writes. Never throws after construction: a
// failure closes the link and `open()` is tried again by its owner (a serial cable
// pulled and put back, a device that appears late).
class Link {
 public:
  virtual ~Link() = default;
  // Opens (or reopens) the link; false with `last_error()` set when it cannot yet.
  virtual bool open() = 0;
  virtual void close() = 0;
  virtual bool is_open() const = 0;
  // Waits up to `timeout` for bytes; returns how many were read into `buffer` (0: none
  // in time). On a failure (device gone) closes the link and returns 0.
  virtual std::size_t read(std::uint8_t* buffer, std::size_t capacity,
                           std::chrono::milliseconds timeout) = 0;
  // Writes a whole frame; false when it could not (no peer yet on udpin, link closed).
  virtual bool write(const std::uint8_t* data, std::size_t size) = 0;
  virtual std::string describe() const = 0;  // e.g. "udpin://0.0.0.0:14540"
  virtual std::string last_error() const = 0;
};

// The link a URL names (not opened yet).
std::unique_ptr<Link> make_link(const ConnectionUrl& url);

// A UDP socket bound to `bind_host:bind_port` that sends to a fixed peer from the start
// (as PX4 SITL's onboard link does: bind 14580 + i, send to 14540 + i) and answers
// nobody else. bind_port 0: an ephemeral port.
std::unique_ptr<Link> make_udp_link(const std::string& bind_host, std::uint16_t bind_port,
                                    const std::string& peer_host, std::uint16_t peer_port);

}  // namespace cover::mavlink
