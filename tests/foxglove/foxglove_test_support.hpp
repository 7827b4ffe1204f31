#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cover/test/file_contents.hpp"
#include "cover/test/wait_until.hpp"
#include "recorder_support.hpp"  // scaled, find_node, decoded_form (tests/mcap)

// What the bridge tests share: the bridge process on a port of the test range, the Node
// Foxglove client whose JSON lines are collected as they come, and a raw WebSocket client.
namespace cover::test {

// Waits for `condition` on a file or another process's output, reading it every 20 ms.
inline bool poll_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  return wait_until(condition, timeout, std::chrono::milliseconds(20));
}

// cover-foxglove-bridge on a port of 20000-32000 (another is tried when it is taken: exit 4).
class BridgeProcess {
 public:
  BridgeProcess(int domain, const std::vector<std::string>& extra, const std::string& log_name) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      port_ = static_cast<std::uint16_t>(20000 + (getpid() * 37 + attempt * 611 + domain) % 12000);
      log_ = scratch_path(log_name);
      process::SpawnOptions options;
      options.log_file = log_;
      std::vector<std::string> argv{
          COVER_FOXGLOVE_BRIDGE, "--port", std::to_string(port_), "--dds", "fastdds", "--domain",
          std::to_string(domain)};
      argv.insert(argv.end(), extra.begin(), extra.end());
      child_ = std::make_unique<process::ChildProcess>(argv, options);
      const bool up = poll_until(
          [&] {
            return read_text(log_).find("serving") != std::string::npos ||
                   child_->wait(std::chrono::milliseconds(0)).has_value();
          },
          std::chrono::seconds(20));
      if (up && !child_->exit_code().has_value() &&
          read_text(log_).find("serving") != std::string::npos) {
        return;
      }
      if (child_->exit_code() != 4) break;  // not a taken port: a real failure
    }
    ADD_FAILURE() << "the bridge did not start: see " << log_;
  }
  std::uint16_t port() const { return port_; }
  std::string url() const { return "ws://127.0.0.1:" + std::to_string(port_); }
  const std::string& log() const { return log_; }
  process::ChildProcess& child() { return *child_; }

 private:
  std::uint16_t port_ = 0;
  std::string log_;
  std::unique_ptr<process::ChildProcess> child_;
};

// tests/foxglove/peer/client.js; its JSON lines are read on a thread as they arrive.
class NodeClient {
 public:
  NodeClient(const std::string& url, const nlohmann::json& options, const std::string& name) {
    process::SpawnOptions spawn;
    spawn.capture_stdout = true;
    spawn.log_file = scratch_path(name + ".stderr");
    child_ = std::make_unique<process::ChildProcess>(
        std::vector<std::string>{find_node(), std::string(COVER_FOXGLOVE_PEER_DIR) + "/client.js",
                                 url, options.dump()},
        spawn);
    reader_ = std::thread([this] {
      while (const auto line = child_->read_line(std::chrono::seconds(120))) {
        nlohmann::json parsed = nlohmann::json::parse(*line, nullptr, false);
        std::lock_guard<std::mutex> lock(mutex_);
        lines_.push_back(std::move(parsed));
        changed_.notify_all();
      }
    });
  }
  ~NodeClient() {
    child_->terminate(std::chrono::seconds(5));
    if (reader_.joinable()) reader_.join();
  }
  std::vector<nlohmann::json> lines() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lines_;
  }
  std::vector<nlohmann::json> events(const std::string& event) const {
    std::vector<nlohmann::json> out;
    for (const auto& l : lines()) {
      if (l.is_object() && l.value("event", "") == event) out.push_back(l);
    }
    return out;
  }
  // Waits until `condition` holds on the lines so far.
  bool wait_for(const std::function<bool(const std::vector<nlohmann::json>&)>& condition,
                std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, scaled(timeout), [&] { return condition(lines_); });
  }

 private:
  std::unique_ptr<process::ChildProcess> child_;
  std::thread reader_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<nlohmann::json> lines_;
};

inline std::size_t count_event(const std::vector<nlohmann::json>& lines, const std::string& event,
                               const std::string& topic = "") {
  std::size_t n = 0;
  for (const auto& l : lines) {
    if (l.is_object() && l.value("event", "") == event &&
        (topic.empty() || l.value("topic", "") == topic)) {
      ++n;
    }
  }
  return n;
}

// A WebSocket client on a bare TCP socket with a small receive buffer: it subscribes, then
// reads nothing (the slow client), or offers what it is told in the handshake.
class RawClient {
 public:
  RawClient(std::uint16_t port, const std::string& subprotocol) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    const int small = 4096;
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) return;
    std::string request =
        "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
        "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n";
    if (!subprotocol.empty()) request += "Sec-WebSocket-Protocol: " + subprotocol + "\r\n";
    request += "\r\n";
    send_all(request);
    // The response head only (the frames after it stay unread).
    char c = 0;
    while (response_.find("\r\n\r\n") == std::string::npos && ::recv(fd_, &c, 1, 0) == 1) {
      response_ += c;
    }
  }
  ~RawClient() {
    if (fd_ >= 0) ::close(fd_);
  }
  const std::string& response() const { return response_; }

  // A masked text frame, as a client must send.
  void send_text(const std::string& text) {
    std::string frame;
    frame += static_cast<char>(0x81);
    if (text.size() < 126) {
      frame += static_cast<char>(0x80 | text.size());
    } else {
      frame += static_cast<char>(0x80 | 126);
      frame += static_cast<char>((text.size() >> 8) & 0xff);
      frame += static_cast<char>(text.size() & 0xff);
    }
    const char mask[4] = {0x12, 0x34, 0x56, 0x78};
    frame.append(mask, 4);
    for (std::size_t i = 0; i < text.size(); ++i) frame += static_cast<char>(text[i] ^ mask[i % 4]);
    send_all(frame);
  }
  // Reads (and discards) until the server closes the connection: true at EOF or reset.
  bool closed_by_server(std::chrono::milliseconds timeout) {
    timeval tv{0, 100'000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    const auto deadline = std::chrono::steady_clock::now() + scaled(timeout);
    char buffer[65536];
    while (std::chrono::steady_clock::now() < deadline) {
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n == 0) return true;
      if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return true;
    }
    return false;
  }

 private:
  void send_all(const std::string& bytes) {
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return;
      sent += static_cast<std::size_t>(n);
    }
  }
  int fd_ = -1;
  std::string response_;
};

}  // namespace cover::test
