#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "link_factories.hpp"

namespace cover::mavlink::detail {
namespace {

struct Address {
  sockaddr_storage storage{};
  socklen_t length = 0;
  bool valid() const { return length > 0; }
  const sockaddr* get() const { return reinterpret_cast<const sockaddr*>(&storage); }
};

// The first datagram address of `host:port`, or an error text in `error`.
bool resolve(const std::string& host, std::uint16_t port, bool passive, int family, Address& out,
             std::string& error) {
  addrinfo hints{};
  hints.ai_family = family;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = AI_NUMERICSERV | (passive ? AI_PASSIVE : 0);
  addrinfo* result = nullptr;
  const std::string service = std::to_string(port);
  const int rc =
      getaddrinfo(host.empty() ? nullptr : host.c_str(), service.c_str(), &hints, &result);
  if (rc != 0 || result == nullptr) {
    error = "cannot resolve '" + host + "': " + gai_strerror(rc);
    return false;
  }
  std::memcpy(&out.storage, result->ai_addr, result->ai_addrlen);
  out.length = result->ai_addrlen;
  freeaddrinfo(result);
  return true;
}

class UdpLink final : public Link {
 public:
  UdpLink(UdpPeerMode mode, UdpEndpoints endpoints, std::string description)
      : mode_(mode), endpoints_(std::move(endpoints)), description_(std::move(description)) {}
  ~UdpLink() override { close(); }

  bool open() override {
    if (is_open()) return true;
    try {
      return open_socket();
    } catch (const std::exception& e) {  // only allocation can throw here
      set_error("%s", e.what());
      return false;
    }
  }

  void close() override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (mode_ == UdpPeerMode::LearnFromSender) peer_ = Address{};
  }

  bool is_open() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return fd_ >= 0;
  }

  std::size_t read(std::uint8_t* buffer, std::size_t capacity,
                   std::chrono::milliseconds timeout) override {
    const int fd = current_fd();  // only the reading thread opens and closes
    if (fd < 0) return 0;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (ready <= 0 || (p.revents & POLLIN) == 0) return 0;
    Address from;
    from.length = sizeof(from.storage);
    const ssize_t n = ::recvfrom(fd, buffer, capacity, 0,
                                 reinterpret_cast<sockaddr*>(&from.storage), &from.length);
    if (n < 0) {
      // ECONNREFUSED: an ICMP answer to an earlier send (the peer is not up yet).
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR || errno == ECONNREFUSED) {
        return 0;
      }
      set_error("receive failed: %s", std::strerror(errno));
      close();
      return 0;
    }
    if (mode_ == UdpPeerMode::LearnFromSender) {
      std::lock_guard<std::mutex> lock(mutex_);
      peer_ = from;
    }
    return static_cast<std::size_t>(n);
  }

  bool write(const std::uint8_t* data, std::size_t size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ < 0) return fail_locked("link closed");
    ssize_t n = -1;
    if (mode_ == UdpPeerMode::Connected) {
      n = ::send(fd_, data, size, MSG_NOSIGNAL);
    } else {
      if (!peer_.valid()) return fail_locked("no peer yet (nothing received on udpin)");
      n = ::sendto(fd_, data, size, MSG_NOSIGNAL, peer_.get(), peer_.length);
    }
    if (n != static_cast<ssize_t>(size)) {
      return fail_locked(n < 0 ? std::strerror(errno) : "short datagram");
    }
    return true;
  }

  std::string describe() const override { return description_; }

  std::string last_error() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_.data();
  }

 private:
  int current_fd() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return fd_;
  }

  bool open_socket() {
    std::string error;
    Address bind_address;
    Address peer;
    int family = AF_UNSPEC;
    if (!endpoints_.bind_host.empty()) {
      if (!resolve(endpoints_.bind_host, endpoints_.bind_port, true, AF_UNSPEC, bind_address,
                   error)) {
        set_error("%s", error.c_str());
        return false;
      }
      family = bind_address.storage.ss_family;
    }
    if (!endpoints_.peer_host.empty()) {
      if (!resolve(endpoints_.peer_host, endpoints_.peer_port, false, family, peer, error)) {
        set_error("%s", error.c_str());
        return false;
      }
      family = peer.storage.ss_family;
    }
    const int fd = ::socket(family, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      set_error("socket: %s", std::strerror(errno));
      return false;
    }
    if (bind_address.valid() && ::bind(fd, bind_address.get(), bind_address.length) != 0) {
      set_error("cannot bind %s:%u: %s", endpoints_.bind_host.c_str(),
                static_cast<unsigned>(endpoints_.bind_port), std::strerror(errno));
      ::close(fd);
      return false;
    }
    if (mode_ == UdpPeerMode::Connected && ::connect(fd, peer.get(), peer.length) != 0) {
      set_error("cannot connect to %s:%u: %s", endpoints_.peer_host.c_str(),
                static_cast<unsigned>(endpoints_.peer_port), std::strerror(errno));
      ::close(fd);
      return false;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    fd_ = fd;
    peer_ = mode_ == UdpPeerMode::LearnFromSender ? Address{} : peer;
    error_[0] = '\0';
    return true;
  }

  // The error text lives in a fixed buffer: a failing write (no peer yet, every sample)
  // must not allocate.
  bool fail_locked(const char* why) {
    std::snprintf(error_.data(), error_.size(), "%s: %s", description_.c_str(), why);
    return false;
  }

  void set_error(const char* format, ...) __attribute__((format(printf, 2, 3))) {
    std::array<char, 256> text{};
    va_list args;
    va_start(args, format);
    std::vsnprintf(text.data(), text.size(), format, args);
    va_end(args);
    std::lock_guard<std::mutex> lock(mutex_);
    fail_locked(text.data());
  }

  const UdpPeerMode mode_;
  const UdpEndpoints endpoints_;
  const std::string description_;
  mutable std::mutex mutex_;  // guards fd_ against a close while the writer writes, peer_
  int fd_ = -1;
  Address peer_;
  std::array<char, 320> error_{};
};

}  // namespace

std::unique_ptr<Link> make_udp(UdpPeerMode mode, UdpEndpoints endpoints, std::string description) {
  return std::make_unique<UdpLink>(mode, std::move(endpoints), std::move(description));
}

}  // namespace cover::mavlink::detail
