#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "cover/ground_station/access.hpp"

namespace cover::ground_station {

struct WebServerOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 8080;  // 0: any free port (port() tells which)
  std::string static_dir;     // the page's files (the build folder's web/)
  AccessPolicy access;
  // Bytes waiting for one client (queued, and again at most as much in its socket): beyond
  // it that client's new messages are dropped, the others are unaffected.
  std::size_t client_queue_bytes = 1024 * 1024;
  // A client whose queue stays full this long (it does not read) is disconnected.
  double slow_client_timeout_s = 2.0;
  std::size_t max_clients = 16;
  // A WebSocket message beyond this closes the connection (1009) before it is buffered.
  std::size_t max_message_bytes = 256 * 1024;
};

struct WebServerStats {
  std::uint64_t clients = 0;
  std::uint64_t connections = 0;
  std::uint64_t http_requests = 0;
  std::uint64_t refused = 0;  // HTTP or WebSocket requests answered 4xx
  std::uint64_t dropped = 0;  // messages a full client queue refused
  std::uint64_t slow_disconnects = 0;
};

// The page's server: static files over HTTP and one WebSocket per page (websocketpp over
// Asio, one I/O thread), every request checked by the AccessPolicy. send() and broadcast()
// may be called from any thread and never block on a socket: each client has a bounded
// queue that the I/O thread drains as fast as that client reads.
class WebServer {
 public:
  // Called on the I/O thread with each text message; must not block (hand work to a thread).
  // `has_token`: the client's WebSocket was opened with the token.
  using MessageHandler =
      std::function<void(std::uint64_t client, bool has_token, const std::string& text)>;
  using OpenHandler = std::function<void(std::uint64_t client)>;

  // Throws std::runtime_error when the address cannot be listened on.
  WebServer(WebServerOptions options, MessageHandler on_message, OpenHandler on_open = {});
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  std::uint16_t port() const;
  void send(std::uint64_t client, const std::string& text);
  void broadcast(const std::string& text);
  WebServerStats stats() const;
  // Closes every connection and stops the I/O thread. Idempotent; the destructor calls it.
  void stop();

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace cover::ground_station
