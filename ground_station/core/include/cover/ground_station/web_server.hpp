#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "cover/ground_station/access.hpp"
#include "cover/websocket/server.hpp"

namespace cover::ground_station {

// The page's transport settings: loopback, port 8080, 1 MiB per page, a page not reading for
// 2 s disconnected, 16 pages, a message beyond 256 KiB closing its connection (1009).
websocket::ServerOptions default_transport();

struct WebServerOptions {
  websocket::ServerOptions transport = default_transport();
  std::string static_dir;  // the page's files (the build folder's web/)
  AccessPolicy access;
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
