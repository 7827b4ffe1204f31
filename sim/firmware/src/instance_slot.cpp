#include "cover/firmware/instance_slot.hpp"

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

namespace cover::firmware {
namespace {

// A bound abstract socket for instance N, or -1 when another process holds it.
int bind_claim(int instance) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("instance claim: socket: ") + strerror(errno));
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string name = "cover-firmware-sitl-" + std::to_string(instance);
  std::memcpy(address.sun_path + 1, name.data(), name.size());  // abstract: leading NUL
  const auto length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + name.size());
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), length) == 0) return fd;
  const int error = errno;
  ::close(fd);
  if (error == EADDRINUSE) return -1;
  throw std::runtime_error("instance claim: bind for " + std::to_string(instance) + ": " +
                           strerror(error));
}

}  // namespace

bool port_free(const PortUse& use) {
  const int fd = ::socket(AF_INET, (use.tcp ? SOCK_STREAM : SOCK_DGRAM) | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);  // the firmware binds every interface
  address.sin_port = htons(static_cast<std::uint16_t>(use.port));
  const bool free = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  ::close(fd);
  return free;
}

InstanceSlot InstanceSlot::claim(Autopilot firmware, int first, int last) {
  std::string taken;
  for (int n = first; n <= last; ++n) {
    const int fd = bind_claim(n);
    if (fd < 0) {
      taken += " " + std::to_string(n) + " (another COVER test)";
      continue;
    }
    bool free = true;
    for (const PortUse& use : ports_of(firmware, n)) {
      if (!port_free(use)) {
        taken += " " + std::to_string(n) + " (" + (use.tcp ? "TCP " : "UDP ") +
                 std::to_string(use.port) + " in use)";
        free = false;
        break;
      }
    }
    if (free) return InstanceSlot(n, fd);
    ::close(fd);
  }
  throw std::runtime_error(std::string("no free ") + display_name(firmware) + " SITL instance in " +
                           std::to_string(first) + ".." + std::to_string(last) + ":" + taken);
}

InstanceSlot::InstanceSlot(InstanceSlot&& other) noexcept
    : instance_(other.instance_), fd_(other.fd_) {
  other.fd_ = -1;
}

InstanceSlot& InstanceSlot::operator=(InstanceSlot&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    instance_ = other.instance_;
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

InstanceSlot::~InstanceSlot() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace cover::firmware
