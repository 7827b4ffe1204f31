#include "cover/vrpn/tracker_client.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace cover::vrpn {
namespace {

constexpr std::size_t kReadChunk = 16384;

std::chrono::milliseconds to_ms(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(std::ceil(seconds * 1e3)));
}

}  // namespace

void parse_server(const std::string& text, std::string& host, std::uint16_t& port) {
  const auto colon = text.rfind(':');
  host = colon == std::string::npos ? text : text.substr(0, colon);
  port = kDefaultPort;
  if (colon != std::string::npos) {
    const std::string digits = text.substr(colon + 1);
    if (digits.empty() || digits.size() > 5 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      throw std::invalid_argument("'" + text + "': the port must be a number (HOST:PORT)");
    }
    const int value = std::stoi(digits);
    if (value < 1 || value > 65535) {
      throw std::invalid_argument("'" + text + "': the port must be in [1, 65535]");
    }
    port = static_cast<std::uint16_t>(value);
  }
  if (host.empty()) throw std::invalid_argument("'" + text + "': no host (HOST:PORT)");
}

TrackerClient::TrackerClient(ClientOptions options)
    : options_(std::move(options)),
      session_(options_.session),
      next_attempt_(Clock::now()),
      backoff_s_(options_.backoff_min_s),
      read_buffer_(kReadChunk) {
  if (options_.session.bodies.empty()) throw std::invalid_argument("VRPN client: no body to track");
  if (!(options_.backoff_min_s > 0.0 && options_.backoff_max_s >= options_.backoff_min_s)) {
    throw std::invalid_argument("VRPN client: back-off must satisfy 0 < min <= max");
  }
  if (!(options_.connect_timeout_s > 0.0 && options_.silence_timeout_s > 0.0)) {
    throw std::invalid_argument("VRPN client: timeouts must be > 0");
  }
}

TrackerClient::~TrackerClient() {
  close_socket();
}

std::string TrackerClient::describe() const {
  return options_.host + ":" + std::to_string(options_.port);
}

ClientStats TrackerClient::stats() const {
  ClientStats s = stats_;
  s.session = session_.stats();
  return s;
}

void TrackerClient::close_socket() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  state_ = State::Idle;
}

void TrackerClient::drop(const std::string& why) {
  const bool was_open = state_ == State::Open && session_.handshake_done();
  close_socket();
  next_attempt_ = Clock::now() + to_ms(backoff_s_);
  if (was_open) {
    ++stats_.disconnects;
    spdlog::warn("VRPN {}: connection lost ({}); again in {:.1f} s", describe(), why, backoff_s_);
  } else if (why != last_failure_) {
    // A server that stays away logs once per reason, not on every attempt.
    spdlog::warn("VRPN {}: cannot connect ({}); trying every {:.1f}..{:.1f} s", describe(), why,
                 options_.backoff_min_s, options_.backoff_max_s);
  }
  last_failure_ = why;
  backoff_s_ = std::min(backoff_s_ * 2.0, options_.backoff_max_s);
}

void TrackerClient::start_connect() {
  ++stats_.connect_attempts;
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(options_.port);
  const int rc = ::getaddrinfo(options_.host.c_str(), port.c_str(), &hints, &found);
  if (rc != 0 || found == nullptr) {
    drop(std::string("host not found: ") + gai_strerror(rc));
    return;
  }
  fd_ = ::socket(found->ai_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) {
    ::freeaddrinfo(found);
    drop(std::string("socket: ") + std::strerror(errno));
    return;
  }
  const int one = 1;
  ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // 64-byte reports, now
  const int result = ::connect(fd_, found->ai_addr, found->ai_addrlen);
  const int error = errno;
  ::freeaddrinfo(found);
  if (result != 0 && error != EINPROGRESS) {
    drop(std::strerror(error));
    return;
  }
  state_ = State::Connecting;
  connect_deadline_ = Clock::now() + to_ms(options_.connect_timeout_s);
  session_.start();
}

void TrackerClient::finish_connect() {
  int error = 0;
  socklen_t length = sizeof error;
  ::getsockopt(fd_, SOL_SOCKET, SO_ERROR, &error, &length);
  if (error != 0) {
    drop(std::strerror(error));
    return;
  }
  state_ = State::Open;
  last_byte_ = Clock::now();
  next_ping_ = last_byte_;
}

void TrackerClient::flush_outgoing() {
  while (fd_ >= 0 && session_.outgoing_bytes() > 0) {
    const ssize_t n =
        ::send(fd_, session_.outgoing(), session_.outgoing_bytes(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      session_.consume_outgoing(static_cast<std::size_t>(n));
    } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
      return;  // the rest goes on a later poll
    } else {
      drop(std::string("send: ") + std::strerror(errno));
      return;
    }
  }
}

void TrackerClient::on_readable(const ReportHandler& on_report) {
  for (;;) {
    const ssize_t n = ::recv(fd_, read_buffer_.data(), read_buffer_.size(), MSG_DONTWAIT);
    if (n == 0) {
      drop("the server closed it");
      return;
    }
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return;
      drop(std::string("recv: ") + std::strerror(errno));
      return;
    }
    last_byte_ = Clock::now();
    const bool had_handshake = session_.handshake_done();
    if (!session_.feed(read_buffer_.data(), static_cast<std::size_t>(n), on_report)) {
      drop(session_.error());
      return;
    }
    if (!had_handshake && session_.handshake_done()) {
      ++stats_.connections;
      backoff_s_ = options_.backoff_min_s;
      last_failure_.clear();
      spdlog::info("VRPN {}: connected, server {}{}", describe(), session_.peer_version(),
                   session_.minor_version_mismatch()
                       ? " (another minor version than ours: should work)"
                       : "");
    }
    flush_outgoing();
    if (fd_ < 0) return;
  }
}

void TrackerClient::poll(std::chrono::milliseconds timeout, const ReportHandler& on_report) {
  const auto now = Clock::now();
  if (state_ == State::Idle) {
    if (now < next_attempt_) {
      const auto wait = std::min(
          timeout, std::chrono::duration_cast<std::chrono::milliseconds>(next_attempt_ - now));
      ::poll(nullptr, 0, static_cast<int>(wait.count()));
      return;
    }
    start_connect();
    if (fd_ < 0) return;
  }
  const bool want_write = session_.outgoing_bytes() > 0 || state_ == State::Connecting;
  pollfd p{fd_, static_cast<short>(POLLIN | (want_write ? POLLOUT : 0)), 0};
  const int ready = ::poll(&p, 1, static_cast<int>(std::max<std::int64_t>(0, timeout.count())));
  if (ready < 0) return;  // EINTR: the caller polls again
  if (state_ == State::Connecting) {
    if (p.revents & (POLLOUT | POLLERR | POLLHUP)) {
      finish_connect();
    } else if (Clock::now() >= connect_deadline_) {
      drop("connect timed out");
    }
    if (state_ != State::Open) return;
  }
  if (p.revents & (POLLIN | POLLERR | POLLHUP)) on_readable(on_report);
  if (fd_ >= 0 && session_.handshake_done() && Clock::now() >= next_ping_) {
    next_ping_ = Clock::now() + to_ms(options_.silence_timeout_s / 4.0);
    const auto wall = std::chrono::system_clock::now().time_since_epoch();
    const auto us = std::chrono::duration_cast<std::chrono::microseconds>(wall).count();
    session_.queue_ping(
        {static_cast<std::int32_t>(us / 1'000'000), static_cast<std::int32_t>(us % 1'000'000)});
  }
  if (fd_ >= 0) flush_outgoing();
  if (fd_ >= 0 && Clock::now() - last_byte_ > to_ms(options_.silence_timeout_s)) {
    drop("no byte for " + std::to_string(options_.silence_timeout_s).substr(0, 4) + " s");
  }
}

}  // namespace cover::vrpn
