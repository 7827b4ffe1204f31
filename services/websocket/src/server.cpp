#include "cover/websocket/server.hpp"

#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <deque>
#include <future>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "cover/clock/clock.hpp"

namespace cover::websocket {
namespace {

using WsServer = websocketpp::server<websocketpp::config::asio>;
using Hdl = websocketpp::connection_hdl;

// The I/O thread's housekeeping period: backlogged queues move on to their sockets as
// those drain, and a client not reading is found.
constexpr auto kTick = std::chrono::milliseconds(10);
// A client closed for not reading whose socket does not even take the close frame is cut.
constexpr std::int64_t kCloseGraceNs = 1'000'000'000;

struct Queued {
  std::string bytes;
  Opcode opcode;
};

struct Client {
  ClientId id = 0;
  Hdl hdl;
  std::string remote;
  std::deque<Queued> queue;  // not yet handed to the socket
  std::size_t queued_bytes = 0;
  std::size_t socket_bytes = 0;  // websocketpp's buffered amount, read on the I/O thread
  bool flush_posted = false;
  std::int64_t full_since_ns = 0;  // monotonic; 0: its queue took the last message
  std::uint64_t dropped = 0;
  std::int64_t closing_since_ns = 0;  // 0: open
};

websocketpp::frame::opcode::value to_ws(Opcode opcode) {
  return opcode == Opcode::Text ? websocketpp::frame::opcode::text
                                : websocketpp::frame::opcode::binary;
}

class ConnectionRequest final : public Request {
 public:
  explicit ConnectionRequest(WsServer::connection_ptr con) : con_(std::move(con)) {}
  std::string method() const override { return con_->get_request().get_method(); }
  std::string resource() const override { return con_->get_resource(); }
  std::string header(const std::string& name) const override {
    return con_->get_request_header(name);
  }
  std::string remote() const override { return con_->get_remote_endpoint(); }
  std::vector<std::string> offered_subprotocols() const override {
    return con_->get_requested_subprotocols();
  }
  void select_subprotocol(const std::string& name) override { con_->select_subprotocol(name); }
  std::string subprotocol() const override { return con_->get_subprotocol(); }
  void set_status(int status) override {
    con_->set_status(static_cast<websocketpp::http::status_code::value>(status));
  }
  void append_header(const std::string& name, const std::string& value) override {
    con_->append_header(name, value);
  }
  void set_body(const std::string& body) override { con_->set_body(body); }

 private:
  WsServer::connection_ptr con_;
};

}  // namespace

class Server::Impl {
 public:
  Impl(ServerOptions options, Handlers handlers);
  ~Impl() { stop(); }

  std::uint16_t port() const { return port_; }
  bool send(ClientId id, std::string message, Opcode opcode);
  void broadcast(const std::string& message, Opcode opcode);
  std::size_t backlog_bytes(ClientId id) const;
  ServerStats stats() const;
  void stop();

 private:
  void listen();
  void on_http(Hdl hdl);
  bool on_validate(Hdl hdl);
  void on_open(Hdl hdl);
  void on_close(Hdl hdl);
  void on_message(Hdl hdl, const WsServer::message_ptr& message);
  // mutex_ held: the message into the client's queue; false when it is closing or full.
  bool enqueue(const std::shared_ptr<Client>& client, std::string message, Opcode opcode,
               std::vector<std::shared_ptr<Client>>& to_flush);
  void post_flushes(std::vector<std::shared_ptr<Client>>& to_flush);
  void flush(const std::shared_ptr<Client>& client);
  void tick();
  void schedule_tick();

  ServerOptions options_;
  Handlers handlers_;
  WsServer ws_;
  std::uint16_t port_ = 0;
  std::thread io_;
  std::promise<void> io_done_;
  std::unique_ptr<asio::steady_timer> tick_timer_;
  std::atomic<bool> stopping_{false};
  std::once_flag stopped_;

  mutable std::mutex mutex_;
  std::map<Hdl, std::shared_ptr<Client>, std::owner_less<Hdl>> clients_;
  std::map<ClientId, std::shared_ptr<Client>> by_id_;
  ClientId next_client_id_ = 1;

  std::atomic<std::uint64_t> connections_{0};
  std::atomic<std::uint64_t> refused_{0};
  std::atomic<std::uint64_t> messages_queued_{0};
  std::atomic<std::uint64_t> bytes_queued_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> slow_disconnects_{0};
};

Server::Impl::Impl(ServerOptions options, Handlers handlers)
    : options_(std::move(options)), handlers_(std::move(handlers)) {
  ws_.clear_access_channels(websocketpp::log::alevel::all);
  ws_.clear_error_channels(websocketpp::log::elevel::all);
  ws_.init_asio();
  ws_.set_reuse_addr(true);
  ws_.set_max_message_size(options_.max_message_bytes);
  ws_.set_max_http_body_size(options_.max_http_body_bytes);
  ws_.set_close_handshake_timeout(1000);
  ws_.set_http_handler([this](Hdl hdl) { on_http(hdl); });
  ws_.set_validate_handler([this](Hdl hdl) { return on_validate(hdl); });
  ws_.set_open_handler([this](Hdl hdl) { on_open(hdl); });
  ws_.set_close_handler([this](Hdl hdl) { on_close(hdl); });
  ws_.set_fail_handler([this](Hdl hdl) { on_close(hdl); });
  ws_.set_message_handler(
      [this](Hdl hdl, WsServer::message_ptr message) { on_message(hdl, message); });
  listen();
  tick_timer_ = std::make_unique<asio::steady_timer>(ws_.get_io_service());
  schedule_tick();
  io_ = std::thread([this] {
    for (;;) {
      try {
        ws_.run();
        break;
      } catch (const std::exception& e) {
        // A handler's exception must not end the server for every client.
        spdlog::error("{}: {} (the I/O loop goes on)", options_.log_name, e.what());
      }
    }
    io_done_.set_value();
  });
}

void Server::Impl::listen() {
  std::error_code ec;
  const auto address = asio::ip::make_address(options_.address, ec);
  if (ec) {
    throw std::runtime_error("bad listen address '" + options_.address + "': " + ec.message());
  }
  ws_.listen(asio::ip::tcp::endpoint(address, options_.port), ec);
  if (ec) {
    throw std::runtime_error("cannot listen on " + options_.address + ":" +
                             std::to_string(options_.port) + ": " + ec.message());
  }
  ws_.start_accept(ec);
  if (ec) throw std::runtime_error("cannot accept connections: " + ec.message());
  const auto local = ws_.get_local_endpoint(ec);
  port_ = ec ? options_.port : local.port();
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

void Server::Impl::on_http(Hdl hdl) {
  ConnectionRequest request(ws_.get_con_from_hdl(hdl));
  if (handlers_.http) {
    handlers_.http(request);
    return;
  }
  request.set_status(404);
  request.set_body("WebSocket only\n");
}

bool Server::Impl::on_validate(Hdl hdl) {
  ConnectionRequest request(ws_.get_con_from_hdl(hdl));
  std::size_t connected = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    connected = clients_.size();
  }
  if (stopping_ || connected >= options_.max_clients) {
    ++refused_;
    spdlog::warn("{}: refused a {} from {}: {} connected already (at most {})", options_.log_name,
                 options_.client_noun, request.remote(), connected, options_.max_clients);
    request.set_status(503);
    request.set_body("too many clients\n");
    return false;
  }
  if (handlers_.validate && !handlers_.validate(request)) {
    ++refused_;
    return false;
  }
  return true;
}

void Server::Impl::on_open(Hdl hdl) {
  auto con = ws_.get_con_from_hdl(hdl);
  auto client = std::make_shared<Client>();
  client->hdl = hdl;
  client->remote = con->get_remote_endpoint();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    client->id = next_client_id_++;
    clients_[hdl] = client;
    by_id_[client->id] = client;
  }
  ++connections_;
  if (handlers_.open) handlers_.open(client->id, ConnectionRequest(con));
}

void Server::Impl::on_close(Hdl hdl) {
  std::shared_ptr<Client> client;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = clients_.find(hdl);
    if (it == clients_.end()) return;  // refused at the handshake
    client = it->second;
    by_id_.erase(client->id);
    clients_.erase(it);
  }
  spdlog::info("{} #{} ({}) left; {} messages dropped for it", options_.client_noun, client->id,
               client->remote, client->dropped);
  if (handlers_.close) handlers_.close(client->id);
}

void Server::Impl::on_message(Hdl hdl, const WsServer::message_ptr& message) {
  ClientId id = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = clients_.find(hdl);
    if (it == clients_.end() || it->second->closing_since_ns != 0) return;
    id = it->second->id;
  }
  if (!handlers_.message) return;
  const Opcode opcode =
      message->get_opcode() == websocketpp::frame::opcode::text ? Opcode::Text : Opcode::Binary;
  handlers_.message(id, opcode, message->get_payload());
}

bool Server::Impl::enqueue(const std::shared_ptr<Client>& client, std::string message,
                           Opcode opcode, std::vector<std::shared_ptr<Client>>& to_flush) {
  if (client->closing_since_ns != 0) return false;
  const std::size_t size = message.size();
  if (client->queued_bytes + client->socket_bytes + size > options_.client_queue_bytes) {
    if (client->full_since_ns == 0) {
      client->full_since_ns = clock::monotonic_ns();
      spdlog::warn(
          "{} #{} ({}) is not keeping up: its queue ({} KiB) is full, new messages "
          "for it are dropped",
          options_.client_noun, client->id, client->remote, options_.client_queue_bytes / 1024);
    }
    ++client->dropped;
    ++dropped_;
    return false;
  }
  client->full_since_ns = 0;
  client->queue.push_back({std::move(message), opcode});
  client->queued_bytes += size;
  ++messages_queued_;
  bytes_queued_ += size;
  if (!client->flush_posted) {
    client->flush_posted = true;
    to_flush.push_back(client);
  }
  return true;
}

void Server::Impl::post_flushes(std::vector<std::shared_ptr<Client>>& to_flush) {
  for (auto& client : to_flush) {
    asio::post(ws_.get_io_service(), [this, client] { flush(client); });
  }
}

bool Server::Impl::send(ClientId id, std::string message, Opcode opcode) {
  if (stopping_) return false;
  std::vector<std::shared_ptr<Client>> to_flush;
  bool queued = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = by_id_.find(id);
    if (it == by_id_.end()) return false;
    queued = enqueue(it->second, std::move(message), opcode, to_flush);
  }
  post_flushes(to_flush);
  return queued;
}

void Server::Impl::broadcast(const std::string& message, Opcode opcode) {
  if (stopping_) return;
  std::vector<std::shared_ptr<Client>> to_flush;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [id, client] : by_id_) enqueue(client, message, opcode, to_flush);
  }
  post_flushes(to_flush);
}

std::size_t Server::Impl::backlog_bytes(ClientId id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = by_id_.find(id);
  return it == by_id_.end() ? 0 : it->second->queued_bytes + it->second->socket_bytes;
}

// On the I/O thread: queued messages into the socket while its buffer holds less than the
// client's bound; the rest waits for the next tick.
void Server::Impl::flush(const std::shared_ptr<Client>& client) {
  std::error_code ec;
  auto con = ws_.get_con_from_hdl(client->hdl, ec);
  if (ec) return;
  std::size_t buffered = con->get_buffered_amount();
  std::vector<Queued> messages;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    client->flush_posted = false;
    while (!client->queue.empty() && buffered < options_.client_queue_bytes) {
      buffered += client->queue.front().bytes.size();
      client->queued_bytes -= client->queue.front().bytes.size();
      messages.push_back(std::move(client->queue.front()));
      client->queue.pop_front();
    }
    client->socket_bytes = buffered;
  }
  for (const auto& m : messages) {
    ws_.send(client->hdl, m.bytes, to_ws(m.opcode), ec);
    if (ec) break;
  }
  buffered = con->get_buffered_amount();
  std::lock_guard<std::mutex> lock(mutex_);
  client->socket_bytes = buffered;
  // It read what a burst had piled up: only a queue that stays full makes a client slow.
  if (client->queue.empty() && buffered < options_.client_queue_bytes / 2) {
    client->full_since_ns = 0;
  }
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
  std::vector<std::shared_ptr<Client>> backlogged, to_close, to_cut;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [hdl, client] : clients_) {
      if (client->closing_since_ns != 0) {
        if (now_ns - client->closing_since_ns > kCloseGraceNs) to_cut.push_back(client);
      } else if (client->full_since_ns != 0 && now_ns - client->full_since_ns > timeout_ns) {
        client->closing_since_ns = now_ns;
        client->queue.clear();  // frees its memory now
        client->queued_bytes = 0;
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
        "{} #{} ({}) disconnected: its queue was full for {:.1f} s (not reading); {} messages "
        "dropped for it",
        options_.client_noun, client->id, client->remote, options_.slow_client_timeout_s,
        client->dropped);
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
  s.refused = refused_;
  s.messages_queued = messages_queued_;
  s.bytes_queued = bytes_queued_;
  s.dropped = dropped_;
  s.slow_disconnects = slow_disconnects_;
  return s;
}

Server::Server(ServerOptions options, Handlers handlers)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(handlers))) {}
Server::~Server() = default;
std::uint16_t Server::port() const {
  return impl_->port();
}
bool Server::send(ClientId client, std::string message, Opcode opcode) {
  return impl_->send(client, std::move(message), opcode);
}
void Server::broadcast(const std::string& message, Opcode opcode) {
  impl_->broadcast(message, opcode);
}
std::size_t Server::backlog_bytes(ClientId client) const {
  return impl_->backlog_bytes(client);
}
ServerStats Server::stats() const {
  return impl_->stats();
}
void Server::stop() {
  impl_->stop();
}

}  // namespace cover::websocket
