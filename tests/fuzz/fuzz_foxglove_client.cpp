// The Foxglove WebSocket bridge's client-message parser (cover_foxglove_protocol), fed any
// bytes a client can send in a text or binary frame (the first byte picks which).
// Contract: no crash, no exception; an Invalid or Unsupported message says why; a
// subscribe holds 1..kMaxIdsPerMessage subscriptions with distinct ids, an unsubscribe at
// most kMaxIdsPerMessage ids; the error status sent back is valid JSON whatever bytes the
// reason quotes; a parsed subscribe / unsubscribe written back as JSON parses to the same
// message; the same bytes parse the same way twice.
#include <nlohmann/json.hpp>

#include <set>
#include <string_view>

#include "cover/foxglove/protocol.hpp"
#include "fuzz_input.hpp"

namespace {

namespace fg = cover::foxglove;
using cover::fuzz::require;

bool same(const fg::ClientMessage& a, const fg::ClientMessage& b) {
  return a.op == b.op && a.subscriptions == b.subscriptions &&
         a.subscription_ids == b.subscription_ids && a.error == b.error;
}

void check(const fg::ClientMessage& m) {
  switch (m.op) {
    case fg::ClientOp::Subscribe: {
      require(!m.subscriptions.empty() && m.subscriptions.size() <= fg::kMaxIdsPerMessage,
              "subscribe of 1..max subscriptions");
      std::set<std::uint32_t> ids;
      for (const auto& s : m.subscriptions) require(ids.insert(s.id).second, "distinct ids");
      nlohmann::json list = nlohmann::json::array();
      for (const auto& s : m.subscriptions)
        list.push_back({{"id", s.id}, {"channelId", s.channel_id}});
      const std::string again = nlohmann::json{{"op", "subscribe"}, {"subscriptions", list}}.dump();
      require(same(fg::parse_client_text(again), m), "subscribe round trip");
      break;
    }
    case fg::ClientOp::Unsubscribe: {
      require(m.subscription_ids.size() <= fg::kMaxIdsPerMessage, "unsubscribe of <= max ids");
      const std::string again =
          nlohmann::json{{"op", "unsubscribe"}, {"subscriptionIds", m.subscription_ids}}.dump();
      require(same(fg::parse_client_text(again), m), "unsubscribe round trip");
      break;
    }
    case fg::ClientOp::Unsupported:
    case fg::ClientOp::Invalid:
      require(!m.error.empty(), "a refused message says why");
      require(nlohmann::json::accept(fg::status_json(fg::StatusLevel::Error, m.error)),
              "the error status is valid JSON");
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool binary = data[0] & 1;
  const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  const fg::ClientMessage m =
      binary ? fg::parse_client_binary(bytes) : fg::parse_client_text(bytes);
  check(m);
  const fg::ClientMessage again =
      binary ? fg::parse_client_binary(bytes) : fg::parse_client_text(bytes);
  require(same(m, again), "the same bytes parse the same way");
  return 0;
}
