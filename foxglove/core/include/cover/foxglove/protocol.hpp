#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

// The Foxglove WebSocket protocol (subprotocols foxglove.websocket.v1 and foxglove.sdk.v1),
// the part this server speaks: JSON text frames serverInfo, advertise, unadvertise and
// status from the server, subscribe and unsubscribe from a client; binary messageData
// frames (opcode 1 | uint32 subscription id | uint64 log time ns | payload, little endian).
namespace cover::foxglove {

inline constexpr const char* kSubprotocolV1 = "foxglove.websocket.v1";
inline constexpr const char* kSubprotocolSdk = "foxglove.sdk.v1";

// A client message longer than this is refused unread (a subscribe of every channel of a
// large fleet is a few KiB).
inline constexpr std::size_t kMaxClientMessageBytes = 64 * 1024;
// JSON nesting deeper than this is refused before it is parsed (a subscribe is 3 deep).
inline constexpr int kMaxClientJsonDepth = 8;
// Subscriptions or ids in one subscribe / unsubscribe.
inline constexpr std::size_t kMaxIdsPerMessage = 4096;

struct SubscriptionRequest {
  std::uint32_t id = 0;
  std::uint32_t channel_id = 0;
  bool operator==(const SubscriptionRequest& o) const {
    return id == o.id && channel_id == o.channel_id;
  }
};

enum class ClientOp {
  Subscribe,
  Unsubscribe,
  Unsupported,  // a valid operation of the protocol this server does not offer
  Invalid,      // not a message of the protocol
};

struct ClientMessage {
  ClientOp op = ClientOp::Invalid;
  std::vector<SubscriptionRequest> subscriptions;  // Subscribe
  std::vector<std::uint32_t> subscription_ids;     // Unsubscribe
  std::string error;                               // Unsupported / Invalid: why
};

// Parses a text frame from a client. Never throws; any bytes give a ClientMessage.
ClientMessage parse_client_text(std::string_view text);
// A binary frame from a client: clientMessageData (1) and serviceCallRequest (2) need
// capabilities this server does not offer; anything else is not of the protocol.
ClientMessage parse_client_binary(std::string_view bytes);

struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding;         // cdr, json
  std::string schema_name;      // cover::idl::UgvImu, foxglove.FrameTransform
  std::string schema;           // the IDL or JSON Schema text
  std::string schema_encoding;  // omgidl, jsonschema
};

enum class StatusLevel : int { Info = 0, Warning = 1, Error = 2 };

std::string server_info_json(const std::string& name, const std::string& session_id);
std::string advertise_json(const std::vector<Channel>& channels);
std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids);
// `message` may hold any bytes (a client's input quoted in an error): invalid UTF-8 is
// replaced, the frame is always valid JSON.
std::string status_json(StatusLevel level, const std::string& message);

inline constexpr std::size_t kMessageDataHeaderBytes = 1 + 4 + 8;
// The binary messageData frame into `out` (replaced).
void message_data_frame(std::uint32_t subscription_id, std::uint64_t log_time_ns,
                        const std::uint8_t* payload, std::size_t size, std::string& out);

}  // namespace cover::foxglove
