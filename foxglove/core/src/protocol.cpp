#include "cover/foxglove/protocol.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <set>

namespace cover::foxglove {
namespace {

using nlohmann::json;

ClientMessage invalid(std::string why) {
  ClientMessage m;
  m.op = ClientOp::Invalid;
  m.error = std::move(why);
  return m;
}

// Brackets outside strings, counted before parsing: a deeply nested document is refused
// without building it.
bool nesting_within(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false;
  bool escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > max_depth) return false;
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return true;
}

bool read_u32(const json& object, const char* key, std::uint32_t& out) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_integer()) return false;
  if (it->is_number_unsigned()) {
    const auto v = it->get<std::uint64_t>();
    if (v > std::numeric_limits<std::uint32_t>::max()) return false;
    out = static_cast<std::uint32_t>(v);
    return true;
  }
  const auto v = it->get<std::int64_t>();
  if (v < 0 || v > std::numeric_limits<std::uint32_t>::max()) return false;
  out = static_cast<std::uint32_t>(v);
  return true;
}

ClientMessage parse_subscribe(const json& doc) {
  const auto list = doc.find("subscriptions");
  if (list == doc.end() || !list->is_array() || list->empty()) {
    return invalid("subscribe: 'subscriptions' must be a non-empty array");
  }
  if (list->size() > kMaxIdsPerMessage) {
    return invalid("subscribe: more than " + std::to_string(kMaxIdsPerMessage) + " subscriptions");
  }
  ClientMessage m;
  m.op = ClientOp::Subscribe;
  std::set<std::uint32_t> ids;
  for (const auto& entry : *list) {
    SubscriptionRequest s;
    if (!entry.is_object() || !read_u32(entry, "id", s.id) ||
        !read_u32(entry, "channelId", s.channel_id)) {
      return invalid("subscribe: each subscription needs 'id' and 'channelId' (uint32)");
    }
    if (!ids.insert(s.id).second) {
      return invalid("subscribe: subscription id " + std::to_string(s.id) + " given twice");
    }
    m.subscriptions.push_back(s);
  }
  return m;
}

ClientMessage parse_unsubscribe(const json& doc) {
  const auto list = doc.find("subscriptionIds");
  if (list == doc.end() || !list->is_array()) {
    return invalid("unsubscribe: 'subscriptionIds' must be an array");
  }
  if (list->size() > kMaxIdsPerMessage) {
    return invalid("unsubscribe: more than " + std::to_string(kMaxIdsPerMessage) + " ids");
  }
  ClientMessage m;
  m.op = ClientOp::Unsubscribe;
  for (const auto& entry : *list) {
    json wrapper = {{"id", entry}};
    std::uint32_t id = 0;
    if (!read_u32(wrapper, "id", id)) return invalid("unsubscribe: ids must be uint32");
    m.subscription_ids.push_back(id);
  }
  return m;
}

bool known_unsupported(const std::string& op) {
  static const std::set<std::string> ops = {"advertise",
                                            "unadvertise",
                                            "getParameters",
                                            "setParameters",
                                            "subscribeParameterUpdates",
                                            "unsubscribeParameterUpdates",
                                            "subscribeConnectionGraph",
                                            "unsubscribeConnectionGraph",
                                            "fetchAsset"};
  return ops.count(op) != 0;
}

}  // namespace

ClientMessage parse_client_text(std::string_view text) {
  if (text.size() > kMaxClientMessageBytes) {
    return invalid("message of " + std::to_string(text.size()) + " bytes (at most " +
                   std::to_string(kMaxClientMessageBytes) + ")");
  }
  if (!nesting_within(text, kMaxClientJsonDepth)) {
    return invalid("JSON nested deeper than " + std::to_string(kMaxClientJsonDepth));
  }
  const json doc = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) return invalid("not JSON");
  if (!doc.is_object()) return invalid("not a JSON object");
  const auto op = doc.find("op");
  if (op == doc.end() || !op->is_string()) return invalid("no 'op' string");
  const std::string name = op->get<std::string>();
  if (name == "subscribe") return parse_subscribe(doc);
  if (name == "unsubscribe") return parse_unsubscribe(doc);
  if (known_unsupported(name)) {
    ClientMessage m;
    m.op = ClientOp::Unsupported;
    m.error = "'" + name + "': a capability this server does not offer";
    return m;
  }
  return invalid("unknown op '" + name + "'");
}

ClientMessage parse_client_binary(std::string_view bytes) {
  if (bytes.empty()) return invalid("empty binary message");
  const auto opcode = static_cast<std::uint8_t>(bytes[0]);
  if (opcode == 1 || opcode == 2) {
    ClientMessage m;
    m.op = ClientOp::Unsupported;
    m.error = opcode == 1 ? "clientMessageData: this server offers no clientPublish"
                          : "serviceCallRequest: this server offers no services";
    return m;
  }
  return invalid("unknown binary opcode " + std::to_string(opcode));
}

std::string server_info_json(const std::string& name, const std::string& session_id) {
  return json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", json::array()},
              {"supportedEncodings", json::array()},
              {"metadata", json::object()},
              {"sessionId", session_id}}
      .dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string advertise_json(const std::vector<Channel>& channels) {
  json list = json::array();
  for (const auto& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  }
  return json{{"op", "advertise"}, {"channels", list}}.dump(-1, ' ', false,
                                                            json::error_handler_t::replace);
}

std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids) {
  return json{{"op", "unadvertise"}, {"channelIds", channel_ids}}.dump();
}

std::string status_json(StatusLevel level, const std::string& message) {
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

void message_data_frame(std::uint32_t subscription_id, std::uint64_t log_time_ns,
                        const std::uint8_t* payload, std::size_t size, std::string& out) {
  out.resize(kMessageDataHeaderBytes + size);
  out[0] = 1;
  for (int i = 0; i < 4; ++i) out[1 + i] = static_cast<char>((subscription_id >> (8 * i)) & 0xff);
  for (int i = 0; i < 8; ++i) out[5 + i] = static_cast<char>((log_time_ns >> (8 * i)) & 0xff);
  if (size > 0)
    out.replace(kMessageDataHeaderBytes, size, reinterpret_cast<const char*>(payload), size);
}

}  // namespace cover::foxglove
