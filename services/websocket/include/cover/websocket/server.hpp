#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace cover::websocket {

using ClientId = std::uint64_t;
enum class Opcode { Text, Binary };

struct ServerOptions {
  std::string log_name = "websocket server";  // names the server in its log lines
  std::string client_noun = "client";         // "client #3 connected", "page #3 connected"
  std::string address = "127.0.0.1";
  std::uint16_t port = 0;  // 0: any free port (port() tells which)
  // Bytes waiting for one client (queued, and again at most as much handed to its socket):
  // beyond it that client's new messages are dropped, the others are unaffected.
  std::size_t client_queue_bytes = 1024 * 1024;
  // A client whose queue stays full this long (it does not read) is disconnected.
  double slow_client_timeout_s = 2.0;
  std::size_t max_clients = 16;
  // A message from a client beyond this closes its connection (1009) before it is buffered.
  std::size_t max_message_bytes = 256 * 1024;
  std::size_t max_http_body_bytes = 64 * 1024;
};

struct ServerStats {
  std::uint64_t clients = 0;          // connected now
  std::uint64_t connections = 0;      // accepted since start
  std::uint64_t refused = 0;          // handshakes refused (too many clients, or the handler)
  std::uint64_t messages_queued = 0;  // messages taken into a client's queue
  std::uint64_t bytes_queued = 0;
  std::uint64_t dropped = 0;           // messages a full client queue refused
  std::uint64_t slow_disconnects = 0;  // clients disconnected for not reading
};

// An HTTP request, or a WebSocket handshake, as a handler sees it: what the client asked,
// and the answer being written (a refused handshake answers with the status and body set).
class Request {
 public:
  virtual ~Request() = default;
  virtual std::string method() const = 0;
  virtual std::string resource() const = 0;                       // "/index.html?token=..."
  virtual std::string header(const std::string& name) const = 0;  // "" when absent
  virtual std::string remote() const = 0;
  virtual std::vector<std::string> offered_subprotocols() const = 0;
  virtual void select_subprotocol(const std::string& name) = 0;
  virtual std::string subprotocol() const = 0;  // the one selected; "" for none
  virtual void set_status(int status) = 0;
  virtual void append_header(const std::string& name, const std::string& value) = 0;
  virtual void set_body(const std::string& body) = 0;
};

// What a protocol on top does. Every handler runs on the server's one I/O thread and must
// not block.
struct Handlers {
  // A WebSocket handshake: true accepts it (after the server's own check of max_clients);
  // false refuses it with the status and body the handler set. Unset: every one accepted.
  std::function<bool(Request& handshake)> validate;
  // A plain HTTP request: the handler writes the answer. Unset: 404.
  std::function<void(Request& request)> http;
  // A client is connected; `handshake` is its opening request (its headers, its protocol).
  std::function<void(ClientId client, const Request& handshake)> open;
  // A client is gone (closed by either side, or cut).
  std::function<void(ClientId client)> close;
  std::function<void(ClientId client, Opcode opcode, const std::string& payload)> message;
};

// A WebSocket server (websocketpp over standalone Asio, one I/O thread) with a bounded
// queue per client, the Foxglove bridge's and the ground station's alike. send() may be
// called from any thread and never blocks on a socket: the message joins the client's
// queue, which the I/O thread drains into its socket as fast as that client reads; a
// client whose queue stays full is disconnected, the others never wait for it.
class Server {
 public:
  // Throws std::runtime_error when the address cannot be listened on.
  Server(ServerOptions options, Handlers handlers);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  std::uint16_t port() const;
  // False when the client is unknown or closing, or its queue is full (the message dropped).
  bool send(ClientId client, std::string message, Opcode opcode);
  // send() to every connected client.
  void broadcast(const std::string& message, Opcode opcode);
  // Bytes waiting for the client (queued and in its socket); 0 for an unknown one.
  std::size_t backlog_bytes(ClientId client) const;
  ServerStats stats() const;
  // Closes every connection and stops the I/O thread. Idempotent; the destructor calls it.
  void stop();

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace cover::websocket
