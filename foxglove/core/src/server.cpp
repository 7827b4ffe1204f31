#include "cover/foxglove/server.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "cover/clock/clock.hpp"
#include "cover/websocket/server.hpp"

namespace cover::foxglove {
namespace {

using websocket::ClientId;
using websocket::Opcode;

constexpr std::uint32_t kMaxChannelId = 65535;

// A client's subscriptions: its subscription ids by channel and back.
struct Subscriptions {
  std::unordered_map<std::uint32_t, std::uint32_t> channel_of;            // sub id -> channel
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> subs_of;  // channel -> sub ids
};

}  // namespace

class Server::Impl {
 public:
  explicit Impl(ServerOptions options);
  ~Impl() { stop(); }

  std::uint16_t port() const { return transport_->port(); }
  std::vector<std::uint32_t> add_channels(std::vector<Channel> channels);
  void remove_channels(const std::vector<std::uint32_t>& ids);
  bool has_subscribers(std::uint32_t channel_id) const {
    return channel_id <= kMaxChannelId &&
           subscribers_[channel_id].load(std::memory_order_relaxed) > 0;
  }
  void publish(std::uint32_t channel_id, std::uint64_t log_time_ns, const std::uint8_t* data,
               std::size_t size);
  ServerStats stats() const;
  void stop() { transport_->stop(); }

 private:
  websocket::Handlers handlers();
  bool on_validate(websocket::Request& handshake);
  void on_open(ClientId client, const websocket::Request& handshake);
  void on_close(ClientId client);
  void on_message(ClientId client, Opcode opcode, const std::string& payload);
  void apply(Subscriptions& subs, const ClientMessage& message, std::vector<std::string>& errors);
  void drop_subscriptions(Subscriptions& subs);
  void send_text(ClientId client, std::string text) {
    transport_->send(client, std::move(text), Opcode::Text);
  }

  ServerOptions options_;
  std::unique_ptr<std::atomic<std::uint32_t>[]> subscribers_;

  mutable std::mutex mutex_;
  std::map<ClientId, Subscriptions> clients_;
  std::map<std::uint32_t, Channel> channels_;
  std::uint32_t next_channel_id_ = 1;

  std::atomic<std::uint64_t> messages_sent_{0};
  std::atomic<std::uint64_t> bytes_sent_{0};
  std::atomic<std::uint64_t> bad_messages_{0};
  // Last: its I/O thread calls the handlers above, so it is made after them and goes first.
  std::unique_ptr<websocket::Server> transport_;
};

Server::Impl::Impl(ServerOptions options)
    : options_(std::move(options)),
      subscribers_(new std::atomic<std::uint32_t>[kMaxChannelId + 1]) {
  for (std::uint32_t i = 0; i <= kMaxChannelId; ++i) subscribers_[i] = 0;
  transport_ = std::make_unique<websocket::Server>(options_.transport, handlers());
}

websocket::Handlers Server::Impl::handlers() {
  websocket::Handlers h;
  h.validate = [this](websocket::Request& handshake) { return on_validate(handshake); };
  h.open = [this](ClientId c, const websocket::Request& handshake) { on_open(c, handshake); };
  h.close = [this](ClientId c) { on_close(c); };
  h.message = [this](ClientId c, Opcode opcode, const std::string& payload) {
    on_message(c, opcode, payload);
  };
  return h;
}

bool Server::Impl::on_validate(websocket::Request& handshake) {
  for (const auto& offered : handshake.offered_subprotocols()) {
    if (offered == kSubprotocolV1 || offered == kSubprotocolSdk) {
      handshake.select_subprotocol(offered);
      return true;
    }
  }
  spdlog::warn("refused a client from {}: it offers neither {} nor {}", handshake.remote(),
               kSubprotocolV1, kSubprotocolSdk);
  handshake.set_status(400);
  return false;
}

void Server::Impl::on_open(ClientId client, const websocket::Request& handshake) {
  std::vector<Channel> channels;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    clients_[client];
    for (const auto& [id, channel] : channels_) channels.push_back(channel);
  }
  spdlog::info("client #{} connected from {} ({}); {} channels advertised", client,
               handshake.remote(), handshake.subprotocol(), channels.size());
  send_text(client, server_info_json(options_.name, std::to_string(clock::system_ns())));
  if (!channels.empty()) send_text(client, advertise_json(channels));
}

void Server::Impl::drop_subscriptions(Subscriptions& subs) {
  for (const auto& [channel, ids] : subs.subs_of) {
    if (channel <= kMaxChannelId) subscribers_[channel] -= static_cast<std::uint32_t>(ids.size());
  }
  subs.subs_of.clear();
  subs.channel_of.clear();
}

void Server::Impl::on_close(ClientId client) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = clients_.find(client);
  if (it == clients_.end()) return;
  drop_subscriptions(it->second);
  clients_.erase(it);
}

void Server::Impl::apply(Subscriptions& client, const ClientMessage& message,
                         std::vector<std::string>& errors) {
  if (message.op == ClientOp::Subscribe) {
    for (const auto& s : message.subscriptions) {
      if (channels_.count(s.channel_id) == 0) {
        errors.push_back("subscribe: no channel " + std::to_string(s.channel_id));
      } else if (client.channel_of.count(s.id) != 0) {
        errors.push_back("subscribe: subscription id " + std::to_string(s.id) + " is in use");
      } else {
        client.channel_of[s.id] = s.channel_id;
        client.subs_of[s.channel_id].push_back(s.id);
        ++subscribers_[s.channel_id];
      }
    }
  } else if (message.op == ClientOp::Unsubscribe) {
    for (const auto id : message.subscription_ids) {
      const auto it = client.channel_of.find(id);
      if (it == client.channel_of.end()) {
        errors.push_back("unsubscribe: no subscription " + std::to_string(id));
        continue;
      }
      auto& subs = client.subs_of[it->second];
      subs.erase(std::remove(subs.begin(), subs.end(), id), subs.end());
      if (subs.empty()) client.subs_of.erase(it->second);
      --subscribers_[it->second];
      client.channel_of.erase(it);
    }
  } else {
    errors.push_back(message.error);
  }
}

void Server::Impl::on_message(ClientId client, Opcode opcode, const std::string& payload) {
  const ClientMessage parsed =
      opcode == Opcode::Text ? parse_client_text(payload) : parse_client_binary(payload);
  std::vector<std::string> errors;
  std::size_t subscriptions = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = clients_.find(client);
    if (it == clients_.end()) return;
    apply(it->second, parsed, errors);
    subscriptions = it->second.channel_of.size();
  }
  if (errors.empty()) {
    spdlog::debug("client #{}: {} subscriptions", client, subscriptions);
    return;
  }
  ++bad_messages_;
  // Only that client hears of it; a client that floods errors without reading gets no more
  // answers than its queue bound allows.
  for (const auto& error : errors) {
    spdlog::warn("client #{}: {}", client, error.substr(0, 200));
    send_text(client, status_json(StatusLevel::Error, error));
  }
}

std::vector<std::uint32_t> Server::Impl::add_channels(std::vector<Channel> channels) {
  std::vector<std::uint32_t> ids;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& channel : channels) {
      if (next_channel_id_ > kMaxChannelId) throw std::runtime_error("too many channels");
      channel.id = next_channel_id_++;
      channels_[channel.id] = channel;
      ids.push_back(channel.id);
    }
  }
  transport_->broadcast(advertise_json(channels), Opcode::Text);
  return ids;
}

void Server::Impl::remove_channels(const std::vector<std::uint32_t>& ids) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto id : ids) {
      channels_.erase(id);
      for (auto& [client, subs] : clients_) {
        const auto of_channel = subs.subs_of.find(id);
        if (of_channel == subs.subs_of.end()) continue;
        for (const auto sub : of_channel->second) subs.channel_of.erase(sub);
        subscribers_[id] -= static_cast<std::uint32_t>(of_channel->second.size());
        subs.subs_of.erase(of_channel);
      }
    }
  }
  transport_->broadcast(unadvertise_json(ids), Opcode::Text);
}

void Server::Impl::publish(std::uint32_t channel_id, std::uint64_t log_time_ns,
                           const std::uint8_t* data, std::size_t size) {
  if (!has_subscribers(channel_id)) return;
  const std::size_t frame_bytes = kMessageDataHeaderBytes + size;
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [client, subs] : clients_) {
    const auto of_channel = subs.subs_of.find(channel_id);
    if (of_channel == subs.subs_of.end()) continue;
    for (const auto sub : of_channel->second) {
      std::string frame;
      message_data_frame(sub, log_time_ns, data, size, frame);
      if (transport_->send(client, std::move(frame), Opcode::Binary)) {
        ++messages_sent_;
        bytes_sent_ += frame_bytes;
      }
    }
  }
}

ServerStats Server::Impl::stats() const {
  const websocket::ServerStats transport = transport_->stats();
  ServerStats s;
  s.clients = transport.clients;
  s.connections = transport.connections;
  s.messages_sent = messages_sent_;
  s.bytes_sent = bytes_sent_;
  s.dropped = transport.dropped;
  s.slow_disconnects = transport.slow_disconnects;
  s.bad_messages = bad_messages_;
  return s;
}

websocket::ServerOptions default_transport() {
  websocket::ServerOptions transport;
  transport.log_name = "foxglove server";
  transport.address = "0.0.0.0";
  transport.port = 8765;
  transport.client_queue_bytes = 4 * 1024 * 1024;
  transport.slow_client_timeout_s = 5.0;
  transport.max_clients = 16;
  transport.max_message_bytes = 4 * kMaxClientMessageBytes;
  return transport;
}

Server::Server(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}
Server::~Server() = default;
std::uint16_t Server::port() const {
  return impl_->port();
}
std::vector<std::uint32_t> Server::add_channels(std::vector<Channel> channels) {
  return impl_->add_channels(std::move(channels));
}
void Server::remove_channels(const std::vector<std::uint32_t>& channel_ids) {
  impl_->remove_channels(channel_ids);
}
bool Server::has_subscribers(std::uint32_t channel_id) const {
  return impl_->has_subscribers(channel_id);
}
void Server::publish(std::uint32_t channel_id, std::uint64_t log_time_ns, const std::uint8_t* data,
                     std::size_t size) {
  impl_->publish(channel_id, log_time_ns, data, size);
}
ServerStats Server::stats() const {
  return impl_->stats();
}
void Server::stop() {
  impl_->stop();
}

}  // namespace cover::foxglove
