#include "cover/firmware/byte_transport.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>

namespace cover::firmware {
namespace {

sockaddr_in loopback(int port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  return address;
}

bool readable(int fd, std::chrono::milliseconds timeout) {
  pollfd p{fd, POLLIN, 0};
  return ::poll(&p, 1, static_cast<int>(timeout.count())) > 0;
}

class UdpTransport final : public ByteTransport {
 public:
  explicit UdpTransport(int peer_port) : peer_(loopback(peer_port)) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_in self = loopback(0);
    if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&self), sizeof(self)) != 0) {
      throw std::runtime_error(std::string("monitor UDP socket: ") + strerror(errno));
    }
  }
  ~UdpTransport() override { ::close(fd_); }
  bool send(const std::uint8_t* data, std::size_t size) override {
    return ::sendto(fd_, data, size, 0, reinterpret_cast<const sockaddr*>(&peer_), sizeof(peer_)) ==
           static_cast<ssize_t>(size);
  }
  std::size_t receive(std::uint8_t* buffer, std::size_t capacity,
                      std::chrono::milliseconds timeout) override {
    if (!readable(fd_, timeout)) return 0;
    const ssize_t n = ::recv(fd_, buffer, capacity, 0);
    return n > 0 ? static_cast<std::size_t>(n) : 0;
  }

 private:
  int fd_ = -1;
  sockaddr_in peer_;
};

class TcpTransport final : public ByteTransport {
 public:
  explicit TcpTransport(int port) : server_(loopback(port)) {}
  ~TcpTransport() override { disconnect(); }
  bool send(const std::uint8_t* data, std::size_t size) override {
    if (fd_ < 0) return false;
    std::size_t sent = 0;
    while (sent < size) {
      const ssize_t n = ::send(fd_, data + sent, size - sent, MSG_NOSIGNAL);
      if (n <= 0) {
        disconnect();
        return false;
      }
      sent += static_cast<std::size_t>(n);
    }
    return true;
  }
  std::size_t receive(std::uint8_t* buffer, std::size_t capacity,
                      std::chrono::milliseconds timeout) override {
    if (fd_ < 0 && !connect_now()) {
      // The server is not up yet: the next attempt after this receive's timeout, at most
      // 100 ms (a retry period, not a synchronisation).
      std::this_thread::sleep_for(std::min(timeout, std::chrono::milliseconds(100)));
      return 0;
    }
    if (!readable(fd_, timeout)) return 0;
    const ssize_t n = ::recv(fd_, buffer, capacity, 0);
    if (n <= 0) {
      disconnect();  // the firmware closed it (it stopped): connect again later
      return 0;
    }
    return static_cast<std::size_t>(n);
  }

 private:
  bool connect_now() {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) return false;
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&server_), sizeof(server_)) != 0) {
      disconnect();
      return false;
    }
    const int one = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
    return true;
  }
  void disconnect() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  sockaddr_in server_;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<ByteTransport> udp_transport(int peer_port) {
  return std::make_unique<UdpTransport>(peer_port);
}

std::unique_ptr<ByteTransport> tcp_transport(int port) {
  return std::make_unique<TcpTransport>(port);
}

}  // namespace cover::firmware
