#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace cover::test {

// A bare HTTP / WebSocket client over one TCP socket to 127.0.0.1, for the ground station's
// API tests: it sends exactly the headers a test gives (a foreign Origin, no token) and can
// stop reading (a slow client), which a browser or a library client would not let a test do.
class RawWs {
 public:
  RawWs() = default;
  ~RawWs() { close(); }
  RawWs(const RawWs&) = delete;
  RawWs& operator=(const RawWs&) = delete;

  // SO_RCVBUF of the next connection (0: the system's): a small one fills at once.
  void set_receive_buffer(int bytes) { receive_buffer_ = bytes; }

  bool connect(std::uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    if (receive_buffer_ > 0)
      ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer_, sizeof receive_buffer_);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }

  // Sends a GET with `headers` ("Name: value\r\n" each); returns the status code (0: none)
  // and the response's headers and body as far as they came within the timeout.
  int get(std::uint16_t port, const std::string& target, const std::string& headers, bool upgrade,
          std::string* response = nullptr) {
    if (!connect(port)) return 0;
    std::string request =
        "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n" + headers;
    if (upgrade) {
      request +=
          "Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\n"
          "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n";
    }
    request += "\r\n";
    send_all(request);
    std::string text;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    // The headers; for a plain GET also its body (the server closes or sets a length).
    while (std::chrono::steady_clock::now() < deadline) {
      const auto end = text.find("\r\n\r\n");
      if (end != std::string::npos && (upgrade || body_complete(text, end))) break;
      char buf[4096];
      if (!readable(100)) continue;
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) break;
      text.append(buf, static_cast<std::size_t>(n));
    }
    if (upgrade) {
      const auto end = text.find("\r\n\r\n");
      if (end != std::string::npos) {
        pending_ = text.substr(end + 4);
        text.resize(end + 4);
      }
    }
    if (response) *response = text;
    if (text.compare(0, 9, "HTTP/1.1 ") != 0) return 0;
    return std::atoi(text.c_str() + 9);
  }

  void send_text(const std::string& payload) {
    std::string frame;
    frame += static_cast<char>(0x81);
    const std::uint64_t n = payload.size();
    if (n < 126) {
      frame += static_cast<char>(0x80 | n);
    } else if (n < 65536) {
      frame += static_cast<char>(0x80 | 126);
      frame += static_cast<char>(n >> 8);
      frame += static_cast<char>(n & 0xff);
    } else {
      frame += static_cast<char>(0x80 | 127);
      for (int i = 7; i >= 0; --i) frame += static_cast<char>((n >> (8 * i)) & 0xff);
    }
    const char mask[4] = {0x11, 0x22, 0x33, 0x44};
    frame.append(mask, 4);
    for (std::size_t i = 0; i < n; ++i) frame += static_cast<char>(payload[i] ^ mask[i % 4]);
    send_all(frame);
  }

  struct Frame {
    int opcode = 0;
    std::string payload;
  };
  // The next frame within `timeout`; nullopt on timeout or a closed socket (closed() says).
  std::optional<Frame> read_frame(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      if (auto f = parse_frame()) return f;
      if (closed_ || std::chrono::steady_clock::now() >= deadline) return std::nullopt;
      if (!readable(20)) continue;
      char buf[65536];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) {
        closed_ = true;
        continue;
      }
      pending_.append(buf, static_cast<std::size_t>(n));
    }
  }
  // The next text frame's payload, skipping others; "" on timeout or close.
  std::string read_text(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      auto f = read_frame(std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now()));
      if (!f) return "";
      if (f->opcode == 1) return f->payload;
      if (f->opcode == 8) {
        close_frames_ = true;
        last_close_code_ = f->payload.size() >= 2
                               ? (static_cast<unsigned char>(f->payload[0]) << 8) |
                                     static_cast<unsigned char>(f->payload[1])
                               : 0;
        return "";
      }
    }
    return "";
  }
  bool closed() const { return closed_ || close_frames_; }
  int close_code() const { return last_close_code_; }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  bool readable(int ms) {
    pollfd p{fd_, POLLIN, 0};
    return ::poll(&p, 1, ms) > 0;
  }
  void send_all(const std::string& data) {
    std::size_t sent = 0;
    while (sent < data.size()) {
      const ssize_t n = ::send(fd_, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return;
      sent += static_cast<std::size_t>(n);
    }
  }
  static bool body_complete(const std::string& text, std::size_t header_end) {
    const auto at = text.find("Content-Length: ");
    if (at == std::string::npos || at > header_end) return true;
    const auto length = std::stoul(text.substr(at + 16));
    return text.size() >= header_end + 4 + length;
  }
  std::optional<Frame> parse_frame() {
    if (pending_.size() < 2) return std::nullopt;
    const auto b = [&](std::size_t i) { return static_cast<unsigned char>(pending_[i]); };
    std::uint64_t n = b(1) & 0x7f;
    std::size_t header = 2;
    if (n == 126) {
      if (pending_.size() < 4) return std::nullopt;
      n = (b(2) << 8) | b(3);
      header = 4;
    } else if (n == 127) {
      if (pending_.size() < 10) return std::nullopt;
      n = 0;
      for (int i = 0; i < 8; ++i) n = (n << 8) | b(2 + static_cast<std::size_t>(i));
      header = 10;
    }
    if (pending_.size() < header + n) return std::nullopt;
    Frame f{b(0) & 0x0f, pending_.substr(header, n)};
    pending_.erase(0, header + n);
    return f;
  }

  int fd_ = -1;
  int receive_buffer_ = 0;
  std::string pending_;
  bool closed_ = false;
  bool close_frames_ = false;
  int last_close_code_ = 0;
};

}  // namespace cover::test
