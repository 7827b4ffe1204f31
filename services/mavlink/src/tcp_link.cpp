#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <arpa/inet.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "cover/mavlink/tcp_server_link.hpp"
#include "link_factories.hpp"

namespace cover::mavlink {
namespace {

using Clock = std::chrono::steady_clock;

// How long a write waits for room in a full send buffer before it gives the frame up (a
// peer that stopped reading): a frame is never half sent unless the peer is gone.
constexpr int kWriteStallMs = 200;

bool resolve_stream(const std::string& host, std::uint16_t port, bool passive,
                    sockaddr_storage& out, socklen_t& length, std::string& error) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICSERV | (passive ? AI_PASSIVE : 0);
  addrinfo* result = nullptr;
  const std::string service = std::to_string(port);
  const int rc =
      getaddrinfo(host.empty() ? nullptr : host.c_str(), service.c_str(), &hints, &result);
  if (rc != 0 || result == nullptr) {
    error = "cannot resolve '" + host + "': " + gai_strerror(rc);
    return false;
  }
  std::memcpy(&out, result->ai_addr, result->ai_addrlen);
  length = result->ai_addrlen;
  freeaddrinfo(result);
  return true;
}

void set_stream_options(int fd) {
  const int one = 1;
  // Frames are small and latency matters (lockstep: every sensor frame waits for its answer).
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
}

// Sends all of `data` on a non-blocking socket; false when the peer is gone or stalled.
bool send_all(int fd, const std::uint8_t* data, std::size_t size, std::string& error) {
  std::size_t sent = 0;
  while (sent < size) {
    const ssize_t n = ::send(fd, data + sent, size - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{fd, POLLOUT, 0};
      if (::poll(&p, 1, kWriteStallMs) > 0) continue;
      error = "the peer stopped reading";
      return false;
    }
    error = std::strerror(errno);
    return false;
  }
  return true;
}

int remaining_ms(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  return left.count() > 0 ? static_cast<int>(left.count()) : 0;
}

// One connected stream socket: read with a timeout; a hang-up or an error closes it.
// Returns bytes read; sets `closed` when the connection ended.
std::size_t read_stream(int fd, std::uint8_t* buffer, std::size_t capacity, bool& closed,
                        std::string& error) {
  const ssize_t n = ::recv(fd, buffer, capacity, 0);
  if (n > 0) return static_cast<std::size_t>(n);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return 0;
  closed = true;
  error = n == 0 ? "the peer closed the connection" : std::strerror(errno);
  return 0;
}

class TcpServer final : public TcpServerLink {
 public:
  TcpServer(std::string host, std::uint16_t port) : host_(std::move(host)), port_(port) {}
  ~TcpServer() override { close(); }

  bool open() override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (listen_fd_ >= 0) return true;
    sockaddr_storage address{};
    socklen_t length = 0;
    if (!resolve_stream(host_, port_, true, address, length, error_)) return false;
    const int fd = ::socket(address.ss_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) return fail_locked("socket: " + std::string(std::strerror(errno)));
    const int one = 1;
    // A restarted simulator rebinds at once although the last connection is in TIME_WAIT.
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(fd, reinterpret_cast<sockaddr*>(&address), length) != 0 || ::listen(fd, 4) != 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      return fail_locked("cannot listen on " + describe() + ": " + why);
    }
    sockaddr_storage bound{};
    socklen_t bound_length = sizeof bound;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &bound_length);
    bound_port_ =
        ntohs(bound.ss_family == AF_INET6 ? reinterpret_cast<sockaddr_in6*>(&bound)->sin6_port
                                          : reinterpret_cast<sockaddr_in*>(&bound)->sin_port);
    listen_fd_ = fd;
    accepted_ = 0;
    error_.clear();
    return true;
  }

  void close() override {
    std::lock_guard<std::mutex> lock(mutex_);
    drop_client_locked();
    if (listen_fd_ >= 0) ::close(listen_fd_);
    listen_fd_ = -1;
    bound_port_ = 0;
  }

  bool is_open() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return listen_fd_ >= 0;
  }

  std::size_t read(std::uint8_t* buffer, std::size_t capacity,
                   std::chrono::milliseconds timeout) override {
    const auto deadline = Clock::now() + timeout;
    for (;;) {
      int listen_fd = -1;
      int client_fd = -1;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        listen_fd = listen_fd_;
        client_fd = client_fd_;
      }
      if (listen_fd < 0) return 0;
      std::array<pollfd, 2> p{{{listen_fd, POLLIN, 0}, {client_fd, POLLIN, 0}}};
      const int ready = ::poll(p.data(), client_fd >= 0 ? 2 : 1, remaining_ms(deadline));
      if (ready < 0 && errno != EINTR) return 0;
      if (ready > 0 && (p[0].revents & POLLIN) != 0) accept_client(listen_fd);
      if (ready > 0 && client_fd >= 0 && (p[1].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        bool closed = false;
        std::string why;
        const std::size_t n = read_stream(client_fd, buffer, capacity, closed, why);
        if (closed) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (client_fd_ == client_fd) drop_client_locked();
          error_ = describe() + ": " + why;
        }
        if (n > 0) return n;
      }
      if (remaining_ms(deadline) == 0) return 0;
    }
  }

  bool write(const std::uint8_t* data, std::size_t size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (client_fd_ < 0) return fail_locked(describe() + ": no client connected");
    std::string why;
    if (!send_all(client_fd_, data, size, why)) {
      drop_client_locked();
      return fail_locked(describe() + ": " + why);
    }
    return true;
  }

  std::string describe() const override {
    const std::string h = host_.find(':') != std::string::npos ? "[" + host_ + "]" : host_;
    return "tcpin://" + h + ":" + std::to_string(port_);
  }

  std::string last_error() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
  }

  std::uint64_t clients_accepted() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return accepted_;
  }
  bool has_client() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return client_fd_ >= 0;
  }
  std::uint16_t local_port() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return bound_port_;
  }

 private:
  // The newest client wins: a peer reconnecting after a drop we have not noticed yet.
  void accept_client(int listen_fd) {
    const int fd = ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) return;
    set_stream_options(fd);
    std::lock_guard<std::mutex> lock(mutex_);
    drop_client_locked();
    client_fd_ = fd;
    ++accepted_;
  }

  void drop_client_locked() {
    if (client_fd_ >= 0) ::close(client_fd_);
    client_fd_ = -1;
  }

  bool fail_locked(const std::string& why) {
    error_ = why;
    return false;
  }

  const std::string host_;
  const std::uint16_t port_;
  mutable std::mutex mutex_;  // the reader accepts and drops; the writer may drop
  int listen_fd_ = -1;
  int client_fd_ = -1;
  std::uint16_t bound_port_ = 0;
  std::uint64_t accepted_ = 0;
  std::string error_;
};

class TcpClient final : public Link {
 public:
  TcpClient(std::string host, std::uint16_t port) : host_(std::move(host)), port_(port) {}
  ~TcpClient() override { close(); }

  bool open() override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ >= 0) return true;
    sockaddr_storage address{};
    socklen_t length = 0;
    if (!resolve_stream(host_, port_, false, address, length, error_)) return false;
    const int fd = ::socket(address.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      error_ = std::string("socket: ") + std::strerror(errno);
      return false;
    }
    if (::connect(fd, reinterpret_cast<sockaddr*>(&address), length) != 0) {
      error_ = "cannot connect to " + describe() + ": " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    set_stream_options(fd);
    fd_ = fd;
    error_.clear();
    return true;
  }

  void close() override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  bool is_open() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return fd_ >= 0;
  }

  std::size_t read(std::uint8_t* buffer, std::size_t capacity,
                   std::chrono::milliseconds timeout) override {
    int fd = -1;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      fd = fd_;
    }
    if (fd < 0) return 0;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return 0;
    bool closed = false;
    std::string why;
    const std::size_t n = read_stream(fd, buffer, capacity, closed, why);
    if (closed) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (fd_ == fd) {
        ::close(fd_);
        fd_ = -1;
      }
      error_ = describe() + ": " + why;
    }
    return n;
  }

  bool write(const std::uint8_t* data, std::size_t size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ < 0) {
      error_ = describe() + ": not connected";
      return false;
    }
    std::string why;
    if (!send_all(fd_, data, size, why)) {
      ::close(fd_);
      fd_ = -1;
      error_ = describe() + ": " + why;
      return false;
    }
    return true;
  }

  std::string describe() const override {
    const std::string h = host_.find(':') != std::string::npos ? "[" + host_ + "]" : host_;
    return "tcp://" + h + ":" + std::to_string(port_);
  }

  std::string last_error() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
  }

 private:
  const std::string host_;
  const std::uint16_t port_;
  mutable std::mutex mutex_;
  int fd_ = -1;
  std::string error_;
};

}  // namespace

std::unique_ptr<TcpServerLink> make_tcp_server_link(const std::string& bind_host,
                                                    std::uint16_t port) {
  return std::make_unique<TcpServer>(bind_host, port);
}

namespace detail {
std::unique_ptr<Link> make_tcp_client(std::string host, std::uint16_t port) {
  return std::make_unique<TcpClient>(std::move(host), port);
}
}  // namespace detail

}  // namespace cover::mavlink
