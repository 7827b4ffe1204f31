#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cover/vrpn/protocol.hpp"
#include "cover/vrpn/stream_framer.hpp"
#include "cover/vrpn/tracker_report.hpp"

namespace cover::vrpn {

struct SessionOptions {
  // The tracker (rigid body) names to report, as the server names them ("UAV_A").
  std::vector<std::string> bodies;
  // Longest message accepted; a longer length puts the stream out of step.
  std::size_t max_message_bytes = 4096;
  // Remote sender / type names remembered per connection (a server sending more is
  // refused past this, counted as names_overflow).
  std::size_t max_remote_names = 512;
};

// What the session refused or handled, counted over its whole life (every connection).
struct SessionStats {
  std::uint64_t messages = 0;
  std::uint64_t poses = 0;           // valid Pos_Quat reports delivered
  std::uint64_t velocities = 0;      // valid Velocity reports delivered
  std::uint64_t lost_samples = 0;    // NaN / zero quaternion / absurd values: body lost
  std::uint64_t wrong_size = 0;      // a known type with a payload of another size
  std::uint64_t unknown_sender = 0;  // an id never described on this connection
  std::uint64_t unknown_type = 0;
  std::uint64_t untracked = 0;  // tracker messages of bodies nobody asked for
  std::uint64_t bad_descriptions = 0;
  std::uint64_t names_overflow = 0;
  std::uint64_t pings_answered = 0;
  std::uint64_t bad_lengths = 0;  // stream out of step: connection dropped
  std::uint64_t bad_cookies = 0;  // not VRPN 07.x: connection dropped
  std::uint64_t minor_version_mismatches = 0;

  std::uint64_t refused() const {
    return lost_samples + wrong_size + unknown_sender + unknown_type + bad_descriptions +
           names_overflow + bad_lengths + bad_cookies;
  }
};

using ReportHandler = std::function<void(const TrackerReport&)>;

// The client side of one VRPN connection, without the socket: bytes in (feed), reports
// out (the handler), bytes to send out (outgoing). Remote ids are mapped by name, per
// connection. Allocates nothing per message once the remote names are known.
class ClientSession {
 public:
  explicit ClientSession(SessionOptions options);

  // A new connection: forgets the remote names, queues our cookie. Stats are kept.
  void start();
  // Returns false when the connection must be dropped (a foreign cookie, a stream out of
  // step); error() says why.
  bool feed(const std::uint8_t* data, std::size_t size, const ReportHandler& on_report);
  // Bytes to write to the socket; drop the written ones with consume_outgoing.
  const std::uint8_t* outgoing() const { return outgoing_.data(); }
  std::size_t outgoing_bytes() const { return outgoing_.size(); }
  void consume_outgoing(std::size_t bytes);
  // Queues a ping (from our first body's sender): a VRPN server answers with a pong, so a
  // live server is never silent, even while it has no frame to send.
  void queue_ping(ServerTime now);
  bool minor_version_mismatch() const { return minor_mismatch_; }

  bool handshake_done() const { return cookie_have_ == kCookieBytes && !failed_; }
  // The server's version string (after the handshake).
  std::string peer_version() const;
  const std::string& error() const { return error_; }
  const SessionStats& stats() const { return stats_; }
  const std::vector<std::string>& bodies() const { return options_.bodies; }

 private:
  enum class TypeKind : std::uint8_t { PosQuat, Velocity, Ping, Other };
  struct RemoteName {
    std::int32_t id = 0;
    std::int16_t value = -1;  // sender: body index (-1 untracked); type: TypeKind
  };
  void on_message(const RawMessage& message, const ReportHandler& on_report);
  void on_description(const RawMessage& message, std::vector<RemoteName>& table, bool is_sender);
  void on_tracker(const RawMessage& message, int body, TypeKind kind,
                  const ReportHandler& on_report);
  void answer_ping(const RawMessage& message, int body);
  void queue_message(std::int32_t sender, std::int32_t type, ServerTime time,
                     const std::uint8_t* payload, std::size_t bytes);
  void queue_description(std::int32_t system_type, std::int32_t id, const std::string& name);
  void fail(const std::string& why);
  static const RemoteName* find(const std::vector<RemoteName>& table, std::int32_t id);

  SessionOptions options_;
  StreamFramer framer_;
  std::array<std::uint8_t, kCookieBytes> cookie_{};
  std::size_t cookie_have_ = 0;
  bool failed_ = false;
  bool minor_mismatch_ = false;
  std::string error_;
  std::vector<RemoteName> senders_;
  std::vector<RemoteName> types_;
  std::vector<std::uint8_t> outgoing_;
  SessionStats stats_;
  MessageHandler message_handler_;
  const ReportHandler* report_handler_ = nullptr;
};

}  // namespace cover::vrpn
