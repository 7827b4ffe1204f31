#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "cover/vrpn/client_session.hpp"

namespace cover::vrpn {

struct ClientOptions {
  std::string host = "127.0.0.1";
  std::uint16_t port = kDefaultPort;
  SessionOptions session;
  double connect_timeout_s = 1.0;
  // After a failed attempt or a lost connection the next attempt waits backoff_min_s,
  // doubled on each failure up to backoff_max_s; a completed handshake resets it.
  double backoff_min_s = 0.1;
  double backoff_max_s = 2.0;
  // No byte from the server for this long: the connection is dead (a server that hangs,
  // a cable pulled without a FIN), dropped and made again. The client pings four times
  // per timeout; a server answers each with a pong, frames or not.
  double silence_timeout_s = 1.0;
};

struct ClientStats {
  std::uint64_t connect_attempts = 0;
  std::uint64_t connections = 0;  // handshakes completed
  std::uint64_t disconnects = 0;
  SessionStats session;
};

// "HOST:PORT" (or "HOST", default port) into host and port; throws std::invalid_argument.
void parse_server(const std::string& text, std::string& host, std::uint16_t& port);

// A VRPN tracker client over TCP: owns the socket, connects, answers the protocol, and
// reconnects with back-off when the server goes away. Single-threaded: poll() does all
// the work. Never throws after construction.
class TrackerClient {
 public:
  // Throws std::invalid_argument on options that cannot work (no body, bad back-off).
  explicit TrackerClient(ClientOptions options);
  ~TrackerClient();
  TrackerClient(const TrackerClient&) = delete;
  TrackerClient& operator=(const TrackerClient&) = delete;

  // Connects when due, waits up to `timeout` for the server's bytes and delivers the
  // reports they hold.
  void poll(std::chrono::milliseconds timeout, const ReportHandler& on_report);

  bool connected() const { return fd_ >= 0 && session_.handshake_done(); }
  ClientStats stats() const;
  const ClientOptions& options() const { return options_; }
  std::string describe() const;

 private:
  enum class State { Idle, Connecting, Open };
  using Clock = std::chrono::steady_clock;
  void start_connect();
  void finish_connect();
  void on_readable(const ReportHandler& on_report);
  void flush_outgoing();
  void drop(const std::string& why);
  void close_socket();

  ClientOptions options_;
  ClientSession session_;
  State state_ = State::Idle;
  int fd_ = -1;
  Clock::time_point next_attempt_;
  Clock::time_point connect_deadline_;
  Clock::time_point last_byte_;
  Clock::time_point next_ping_;
  double backoff_s_;
  std::string last_failure_;
  std::vector<std::uint8_t> read_buffer_;
  ClientStats stats_;
};

}  // namespace cover::vrpn
