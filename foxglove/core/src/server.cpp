#include "cover/foxglove/server.hpp"

#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <deque>
#include <future>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <utility>

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "cover/clock/clock.hpp"

namespace cover::foxglove {
namespace {

using WsServer = websocketpp::server<websocketpp::config::asio>;
using Hdl = websocketpp::connection_hdl;
using Opcode = websocketpp::frame::opcode::value;

constexpr std::uint32_t kMaxChannelId = 65535;
// The I/O thread's housekeeping period: a backlogged client's queue is moved on to its
// socket as the socket drains, and a client not reading is found.
constexpr auto kTick = std::chrono::milliseconds(10);
// A client closed for not reading whose socket still does not take the close frame is cut.
constexpr std::int64_t kCloseGraceNs = 1'000'000'000;

struct Client {
  std::uint64_t id = 0;
  Hdl hdl;
  std::string remote;
  std::unordered_map<std::uint32_t, std::uint32_t> channel_of;            // sub id -> channel
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> subs_of;  // channel -> sub ids
  std::deque<std::string> queue;  // messageData frames not yet handed to the socket
  std::size_t queued_bytes = 0;
  std::size_t socket_bytes = 0;  // websocketpp's buffered amount, read on the I/O thread
  bool flush_posted = false;
  std::int64_t full_since_ns = 0;  // monotonic; 0: its queue took the last message
  std::uint64_t dropped = 0;
  std::int64_t closing_since_ns = 0;  // 0: open
};

}  // namespace

class Server::Impl {
 public:
  explicit Impl(ServerOptions options);
  ~Impl() { stop(); }

  std::uint16_t port() const { return port_; }
  std::vector<std::uint32_t> add_channels(std::vector<Channel> channels);
  void remove_channels(const std::vector<std::uint32_t>& ids);
  bool has_subscribers(std::uint32_t channel_id) const {
    return channel_id <= kMaxChannelId &&
           subscribers_[channel_id].load(std::memory_order_relaxed) > 0;
  }
  void publish(std::uint32_t channel_id, std::uint64_t log_time_ns, const std::uint8_t* data,
               std::size_t size);
  ServerStats stats() const;
  void stop();

 private:
  bool on_validate(Hdl hdl);
  void on_open(Hdl hdl);
  void on_close(Hdl hdl);
  void on_message(Hdl hdl, WsServer::message_ptr message);
  void apply(Client& client, const ClientMessage& message, std::vector<std::string>& errors);
  void flush(const std::shared_ptr<Client>& client);
  void tick();
  void schedule_tick();
  void send_text(Hdl hdl, const std::string& text);
  void drop_subscriptions(Client& client);

  ServerOptions options_;
  WsServer ws_;
  std::uint16_t port_ = 0;
  std::thread io_;
  std::promise<void> io_done_;
  std::unique_ptr<asio::steady_timer> tick_timer_;
  std::atomic<bool> stopping_{false};
  std::once_flag stopped_;

  mutable std::mutex mutex_;
  std::map<Hdl, std::shared_ptr<Client>, std::owner_less<Hdl>> clients_;
  std::map<std::uint32_t, Channel> channels_;
  std::uint32_t next_channel_id_ = 1;
  std::uint64_t next_client_id_ = 1;
  std::unique_ptr<std::atomic<std::uint32_t>[]> subscribers_;

  std::atomic<std::uint64_t> connections_{0};
  std::atomic<std::uint64_t> messages_sent_{0};
  std::atomic<std::uint64_t> bytes_sent_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> slow_disconnects_{0};
  std::atomic<std::uint64_t> bad_messages_{0};
};

Server::Impl::Impl(ServerOptions options)
    : options_(std::move(options)),
      subscribers_(new std::atomic<std::uint32_t>[kMaxChannelId + 1]) {
  for (std::uint32_t i = 0; i <= kMaxChannelId; ++i) subscribers_[i] = 0;
  ws_.clear_access_channels(websocketpp::log::alevel::all);
  ws_.clear_error_channels(websocketpp::log::elevel::all);
  ws_.init_asio();
  ws_.set_reuse_addr(true);
  // A client's message beyond this closes its connection (1009) before it is buffered
  // whole; up to it, the parser answers an oversized one with an error status.
  ws_.set_max_message_size(4 * kMaxClientMessageBytes);
  ws_.set_close_handshake_timeout(1000);
  ws_.set_validate_handler([this](Hdl hdl) { return on_validate(hdl); });
  ws_.set_open_handler([this](Hdl hdl) { on_open(hdl); });
  ws_.set_close_handler([this](Hdl hdl) { on_close(hdl); });
  ws_.set_fail_handler([this](Hdl hdl) { on_close(hdl); });
  ws_.set_message_handler(
      [this](Hdl hdl, WsServer::message_ptr message) { on_message(hdl, std::move(message)); });
  std::error_code ec;
  const auto address = asio::ip::make_address(options_.address, ec);
  if (ec)
    throw std::runtime_error("bad listen address '" + options_.address + "': " + ec.message());
  ws_.listen(asio::ip::tcp::endpoint(address, options_.port), ec);
  if (ec) {
    throw std::runtime_error("cannot listen on " + options_.address + ":" +
                             std::to_string(options_.port) + ": " + ec.message());
  }
  ws_.start_accept(ec);
  if (ec) throw std::runtime_error("cannot accept connections: " + ec.message());
  const auto local = ws_.get_local_endpoint(ec);
  port_ = ec ? options_.port : local.port();
  tick_timer_ = std::make_unique<asio::steady_timer>(ws_.get_io_service());
  schedule_tick();
  io_ = std::thread([this] {
    for (;;) {
      try {
        ws_.run();
        break;
      } catch (const std::exception& e) {
        // A handler's exception must not end the server for every client.
        spdlog::error("foxglove server: {} (the I/O loop goes on)", e.what());
      }
    }
    io_done_.set_value();
  });
}

void Server::Impl::stop() {
  std::call_once(stopped_, [this] {
    stopping_ = true;
    asio::post(ws_.get_io_service(), [this] {
      std::error_code ec;
      ws_.stop_listening(ec);
      tick_timer_->cancel();
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& [hdl, client] : clients_) {
        ws_.close(hdl, websocketpp::close::status::going_away, "server stopping", ec);
      }
    });
    // Clients that take their close frame leave at once; one that does not read is cut.
    if (io_done_.get_future().wait_for(std::chrono::seconds(2)) != std::future_status::ready) {
      ws_.stop();
    }
    if (io_.joinable()) io_.join();
  });
}

bool Server::Impl::on_validate(Hdl hdl) {
  auto con = ws_.get_con_from_hdl(hdl);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ || clients_.size() >= options_.max_clients) {
      spdlog::warn("refused a client from {}: {} clients already (--max-clients)",
                   con->get_remote_endpoint(), clients_.size());
      con->set_status(websocketpp::http::status_code::service_unavailable);
      return false;
    }
  }
  for (const auto& offered : con->get_requested_subprotocols()) {
    if (offered == kSubprotocolV1 || offered == kSubprotocolSdk) {
      con->select_subprotocol(offered);
      return true;
    }
  }
  spdlog::warn("refused a client from {}: it offers neither {} nor {}", con->get_remote_endpoint(),
               kSubprotocolV1, kSubprotocolSdk);
  con->set_status(websocketpp::http::status_code::bad_request);
  return false;
}

void Server::Impl::send_text(Hdl hdl, const std::string& text) {
  std::error_code ec;
  ws_.send(hdl, text, websocketpp::frame::opcode::text, ec);
}

void Server::Impl::on_open(Hdl hdl) {
  auto con = ws_.get_con_from_hdl(hdl);
  auto client = std::make_shared<Client>();
  client->hdl = hdl;
  client->remote = con->get_remote_endpoint();
  std::vector<Channel> channels;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    client->id = next_client_id_++;
    clients_[hdl] = client;
    for (const auto& [id, channel] : channels_) channels.push_back(channel);
  }
  ++connections_;
  spdlog::info("client #{} connected from {} ({}); {} channels advertised", client->id,
               client->remote, con->get_subprotocol(), channels.size());
  send_text(hdl, server_info_json(options_.name, std::to_string(clock::system_ns())));
  if (!channels.empty()) send_text(hdl, advertise_json(channels));
}

void Server::Impl::drop_subscriptions(Client& client) {
  for (const auto& [channel, subs] : client.subs_of) {
    if (channel <= kMaxChannelId) subscribers_[channel] -= static_cast<std::uint32_t>(subs.size());
  }
  client.subs_of.clear();
  client.channel_of.clear();
  client.queue.clear();
  client.queued_bytes = 0;
}

void Server::Impl::on_close(Hdl hdl) {
  std::shared_ptr<Client> client;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = clients_.find(hdl);
    if (it == clients_.end()) return;  // refused at the handshake
    client = it->second;
    drop_subscriptions(*client);
    clients_.erase(it);
  }
  spdlog::info("client #{} ({}) left; {} messages dropped for it", client->id, client->remote,
               client->dropped);
}

void Server::Impl::apply(Client& client, const ClientMessage& message,
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

void Server::Impl::on_message(Hdl hdl, WsServer::message_ptr message) {
  const std::string& payload = message->get_payload();
  const ClientMessage parsed = message->get_opcode() == websocketpp::frame::opcode::text
                                   ? parse_client_text(payload)
                                   : parse_client_binary(payload);
  std::vector<std::string> errors;
  std::uint64_t client_id = 0;
  std::size_t subscriptions = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = clients_.find(hdl);
    if (it == clients_.end()) return;
    apply(*it->second, parsed, errors);
    client_id = it->second->id;
    subscriptions = it->second->channel_of.size();
  }
  if (errors.empty()) {
    spdlog::debug("client #{}: {} subscriptions", client_id, subscriptions);
    return;
  }
  ++bad_messages_;
  // Only that client hears of it; a client that floods errors without reading gets no more
  // answers than its queue bound allows.
  auto con = ws_.get_con_from_hdl(hdl);
  for (const auto& error : errors) {
    spdlog::warn("client #{}: {}", client_id, error.substr(0, 200));
    if (con->get_buffered_amount() < options_.client_queue_bytes) {
      send_text(hdl, status_json(StatusLevel::Error, error));
    }
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
  asio::post(ws_.get_io_service(), [this, channels] {
    std::vector<Hdl> hdls;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& [hdl, client] : clients_) hdls.push_back(hdl);
    }
    const std::string text = advertise_json(channels);
    for (const auto& hdl : hdls) send_text(hdl, text);
  });
  return ids;
}

void Server::Impl::remove_channels(const std::vector<std::uint32_t>& ids) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto id : ids) {
      channels_.erase(id);
      for (auto& [hdl, client] : clients_) {
        const auto subs = client->subs_of.find(id);
        if (subs == client->subs_of.end()) continue;
        for (const auto sub : subs->second) client->channel_of.erase(sub);
        subscribers_[id] -= static_cast<std::uint32_t>(subs->second.size());
        client->subs_of.erase(subs);
      }
    }
  }
  asio::post(ws_.get_io_service(), [this, ids] {
    std::vector<Hdl> hdls;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& [hdl, client] : clients_) hdls.push_back(hdl);
    }
    const std::string text = unadvertise_json(ids);
    for (const auto& hdl : hdls) send_text(hdl, text);
  });
}

void Server::Impl::publish(std::uint32_t channel_id, std::uint64_t log_time_ns,
                           const std::uint8_t* data, std::size_t size) {
  if (!has_subscribers(channel_id) || stopping_) return;
  const std::size_t frame_bytes = kMessageDataHeaderBytes + size;
  std::vector<std::shared_ptr<Client>> to_flush;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [hdl, client] : clients_) {
      const auto subs = client->subs_of.find(channel_id);
      if (subs == client->subs_of.end() || client->closing_since_ns != 0) continue;
      for (const auto sub : subs->second) {
        if (client->queued_bytes + client->socket_bytes + frame_bytes >
            options_.client_queue_bytes) {
          if (client->full_since_ns == 0) {
            client->full_since_ns = clock::monotonic_ns();
            spdlog::warn(
                "client #{} ({}) is not keeping up: its queue ({} KiB) is full, new "
                "messages for it are dropped",
                client->id, client->remote, options_.client_queue_bytes / 1024);
          }
          ++client->dropped;
          ++dropped_;
          continue;
        }
        client->full_since_ns = 0;
        client->queue.emplace_back();
        message_data_frame(sub, log_time_ns, data, size, client->queue.back());
        client->queued_bytes += frame_bytes;
        ++messages_sent_;
        bytes_sent_ += frame_bytes;
      }
      if (!client->queue.empty() && !client->flush_posted) {
        client->flush_posted = true;
        to_flush.push_back(client);
      }
    }
  }
  for (auto& client : to_flush) {
    asio::post(ws_.get_io_service(), [this, client] { flush(client); });
  }
}

// On the I/O thread: hands queued frames to the socket while its buffer holds less than
// the client's bound; the rest waits for the next tick.
void Server::Impl::flush(const std::shared_ptr<Client>& client) {
  std::error_code ec;
  auto con = ws_.get_con_from_hdl(client->hdl, ec);
  if (ec) return;
  std::size_t buffered = con->get_buffered_amount();
  std::vector<std::string> frames;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    client->flush_posted = false;
    while (!client->queue.empty() && buffered < options_.client_queue_bytes) {
      buffered += client->queue.front().size();
      client->queued_bytes -= client->queue.front().size();
      frames.push_back(std::move(client->queue.front()));
      client->queue.pop_front();
    }
    client->socket_bytes = buffered;
  }
  for (const auto& frame : frames) {
    ws_.send(client->hdl, frame, websocketpp::frame::opcode::binary, ec);
    if (ec) break;
  }
  buffered = con->get_buffered_amount();
  std::lock_guard<std::mutex> lock(mutex_);
  client->socket_bytes = buffered;
}

void Server::Impl::schedule_tick() {
  tick_timer_->expires_after(kTick);
  tick_timer_->async_wait([this](const std::error_code& ec) {
    if (ec || stopping_) return;
    tick();
    schedule_tick();
  });
}

void Server::Impl::tick() {
  const std::int64_t now_ns = clock::monotonic_ns();
  const auto timeout_ns = static_cast<std::int64_t>(options_.slow_client_timeout_s * 1e9);
  std::vector<std::shared_ptr<Client>> backlogged;
  std::vector<std::shared_ptr<Client>> to_close;
  std::vector<std::shared_ptr<Client>> to_cut;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [hdl, client] : clients_) {
      if (client->closing_since_ns != 0) {
        if (now_ns - client->closing_since_ns > kCloseGraceNs) to_cut.push_back(client);
      } else if (client->full_since_ns != 0 && now_ns - client->full_since_ns > timeout_ns) {
        client->closing_since_ns = now_ns;
        drop_subscriptions(*client);  // frees its queue now
        to_close.push_back(client);
      } else if (!client->queue.empty() || client->socket_bytes > 0) {
        backlogged.push_back(client);
      }
    }
  }
  for (auto& client : backlogged) flush(client);
  std::error_code ec;
  for (auto& client : to_close) {
    ++slow_disconnects_;
    spdlog::warn(
        "client #{} ({}) disconnected: its queue was full for {:.1f} s (not reading); "
        "{} messages dropped for it",
        client->id, client->remote, options_.slow_client_timeout_s, client->dropped);
    ws_.close(client->hdl, websocketpp::close::status::policy_violation, "not reading", ec);
  }
  for (auto& client : to_cut) {
    // Its socket does not even take the close frame: cut it (websocketpp then ends the
    // connection and on_close runs).
    auto con = ws_.get_con_from_hdl(client->hdl, ec);
    if (!ec) con->get_raw_socket().close(ec);
  }
}

ServerStats Server::Impl::stats() const {
  ServerStats s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.clients = clients_.size();
  }
  s.connections = connections_;
  s.messages_sent = messages_sent_;
  s.bytes_sent = bytes_sent_;
  s.dropped = dropped_;
  s.slow_disconnects = slow_disconnects_;
  s.bad_messages = bad_messages_;
  return s;
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
