#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cover/foxglove/protocol.hpp"
#include "cover/websocket/server.hpp"

namespace cover::foxglove {

// The live view's transport settings: every interface, port 8765, 4 MiB per client, a
// client not reading for 5 s disconnected, 16 clients; a client's message beyond four times
// kMaxClientMessageBytes closes its connection (1009) before it is buffered whole (up to it,
// the parser answers an oversized one with an error status).
websocket::ServerOptions default_transport();

struct ServerOptions {
  std::string name = "cover-foxglove-bridge";  // serverInfo.name
  websocket::ServerOptions transport = default_transport();
};

struct ServerStats {
  std::uint64_t clients = 0;        // connected now
  std::uint64_t connections = 0;    // accepted since start
  std::uint64_t messages_sent = 0;  // messageData frames queued to clients
  std::uint64_t bytes_sent = 0;
  std::uint64_t dropped = 0;           // messageData frames a full client queue refused
  std::uint64_t slow_disconnects = 0;  // clients dropped for not reading
  std::uint64_t bad_messages = 0;      // client messages answered with an error status
};

// A Foxglove WebSocket server (websocketpp over Asio, one I/O thread). Channels are
// advertised to every client as it connects and when added later. publish() may be
// called from any thread (the DDS receive threads): it never blocks on a socket; it
// copies the frame into each subscribed client's bounded queue, which the I/O thread
// drains into that client's socket as fast as it reads.
class Server {
 public:
  // Throws std::runtime_error when the address cannot be listened on.
  explicit Server(ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  std::uint16_t port() const;
  // Gives each channel its id (channel.id is ignored) and advertises them; returns the ids.
  std::vector<std::uint32_t> add_channels(std::vector<Channel> channels);
  void remove_channels(const std::vector<std::uint32_t>& channel_ids);
  // True when some client subscribes to the channel (lock-free: ask before serializing).
  bool has_subscribers(std::uint32_t channel_id) const;
  void publish(std::uint32_t channel_id, std::uint64_t log_time_ns, const std::uint8_t* data,
               std::size_t size);
  ServerStats stats() const;
  // Closes every connection and stops the I/O thread. Idempotent; the destructor calls it.
  void stop();

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace cover::foxglove
