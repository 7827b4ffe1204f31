#pragma once

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <random>
#include <stdexcept>
#include <thread>
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"

namespace cover::sim::fc::test {

using cover::test::scaled;
using cover::test::wait_until;

inline bool udp_port_free(std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(port);
  const bool free = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  ::close(fd);
  return free;
}

// The first of `count` consecutive loopback UDP ports free now (tests run in parallel:
// never the autopilots' default ports). A port may be taken between this check and its
// use; the caller's bind then fails loudly.
inline std::uint16_t free_port_base(int count) {
  std::mt19937 rng(
      static_cast<unsigned>(::getpid()) ^
      static_cast<unsigned>(std::chrono::steady_clock::now().time_since_epoch().count()));
  // Below Linux's ephemeral range (32768-60999): a port checked free here cannot be taken
  // by a socket some process (the test's own DDS participant) binds to port 0 meanwhile.
  std::uniform_int_distribution<int> pick(20000, 32000);
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int base = pick(rng);
    bool all = true;
    for (int i = 0; i < count && all; ++i)
      all = udp_port_free(static_cast<std::uint16_t>(base + i));
    if (all) return static_cast<std::uint16_t>(base);
  }
  throw std::runtime_error("no free UDP port range on 127.0.0.1");
}

}  // namespace cover::sim::fc::test
