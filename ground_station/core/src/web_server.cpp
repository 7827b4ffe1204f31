#include "cover/ground_station/web_server.hpp"

#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <deque>
#include <fstream>
#include <future>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "cover/clock/clock.hpp"

namespace cover::ground_station {
namespace {

using WsServer = websocketpp::server<websocketpp::config::asio>;
using Hdl = websocketpp::connection_hdl;

// The I/O thread's housekeeping period: backlogged queues move on to their sockets as
// those drain, and a client not reading is found.
constexpr auto kTick = std::chrono::milliseconds(10);
// A client closed for not reading whose socket does not take the close frame is cut.
constexpr std::int64_t kCloseGraceNs = 1'000'000'000;
// The largest file served (the page's bundle is ~1 MB).
constexpr std::size_t kMaxFileBytes = 16 * 1024 * 1024;

struct Client {
  std::uint64_t id = 0;
  Hdl hdl;
  std::string remote;
  bool has_token = false;
  std::deque<std::string> queue;
  std::size_t queued_bytes = 0;
  std::size_t socket_bytes = 0;
  bool flush_posted = false;
  std::int64_t full_since_ns = 0;
  std::uint64_t dropped = 0;
  std::int64_t closing_since_ns = 0;
};

}  // namespace

class WebServer::Impl {
 public:
  Impl(WebServerOptions options, MessageHandler on_message, OpenHandler on_open);
  ~Impl() { stop(); }

  std::uint16_t port() const { return port_; }
  void send(std::uint64_t client, const std::string& text);
  void broadcast(const std::string& text);
  WebServerStats stats() const;
  void stop();

 private:
  AccessDecision check(const WsServer::connection_ptr& con) const;
  void on_http(Hdl hdl);
  bool on_validate(Hdl hdl);
  void on_open(Hdl hdl);
  void on_close(Hdl hdl);
  // mutex_ held: `text` into the client's queue, or dropped when the queue is full.
  void enqueue(Client& client, const std::string& text,
               std::vector<std::shared_ptr<Client>>& to_flush);
  void flush(const std::shared_ptr<Client>& client);
  void tick();
  void schedule_tick();

  WebServerOptions options_;
  MessageHandler on_message_;
  OpenHandler on_open_;
  WsServer ws_;
  std::uint16_t port_ = 0;
  std::thread io_;
  std::promise<void> io_done_;
  std::unique_ptr<asio::steady_timer> tick_timer_;
  std::atomic<bool> stopping_{false};
  std::once_flag stopped_;

  mutable std::mutex mutex_;
  std::map<Hdl, std::shared_ptr<Client>, std::owner_less<Hdl>> clients_;
  std::map<std::uint64_t, std::shared_ptr<Client>> by_id_;
  std::uint64_t next_client_id_ = 1;
  std::map<Hdl, bool, std::owner_less<Hdl>> validated_token_;  // handshake -> has_token

  std::atomic<std::uint64_t> connections_{0};
  std::atomic<std::uint64_t> http_requests_{0};
  std::atomic<std::uint64_t> refused_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> slow_disconnects_{0};
};

WebServer::Impl::Impl(WebServerOptions options, MessageHandler message_handler,
                      OpenHandler open_handler)
    : options_(std::move(options)),
      on_message_(std::move(message_handler)),
      on_open_(std::move(open_handler)) {
  ws_.clear_access_channels(websocketpp::log::alevel::all);
  ws_.clear_error_channels(websocketpp::log::elevel::all);
  ws_.init_asio();
  ws_.set_reuse_addr(true);
  ws_.set_max_message_size(options_.max_message_bytes);
  ws_.set_max_http_body_size(64 * 1024);
  ws_.set_close_handshake_timeout(1000);
  ws_.set_http_handler([this](Hdl hdl) { on_http(hdl); });
  ws_.set_validate_handler([this](Hdl hdl) { return on_validate(hdl); });
  ws_.set_open_handler([this](Hdl hdl) { on_open(hdl); });
  ws_.set_close_handler([this](Hdl hdl) { on_close(hdl); });
  ws_.set_fail_handler([this](Hdl hdl) { on_close(hdl); });
  ws_.set_message_handler([this](Hdl hdl, WsServer::message_ptr message) {
    if (message->get_opcode() != websocketpp::frame::opcode::text) return;
    std::uint64_t id = 0;
    bool has_token = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const auto it = clients_.find(hdl);
      if (it == clients_.end()) return;
      id = it->second->id;
      has_token = it->second->has_token;
    }
    on_message_(id, has_token, message->get_payload());
  });
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
        spdlog::error("ground station server: {} (the I/O loop goes on)", e.what());
      }
    }
    io_done_.set_value();
  });
}

void WebServer::Impl::stop() {
  std::call_once(stopped_, [this] {
    stopping_ = true;
    asio::post(ws_.get_io_service(), [this] {
      std::error_code ec;
      ws_.stop_listening(ec);
      tick_timer_->cancel();
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& [hdl, client] : clients_)
        ws_.close(hdl, websocketpp::close::status::going_away, "server stopping", ec);
    });
    if (io_done_.get_future().wait_for(std::chrono::seconds(2)) != std::future_status::ready)
      ws_.stop();
    if (io_.joinable()) io_.join();
  });
}

AccessDecision WebServer::Impl::check(const WsServer::connection_ptr& con) const {
  return check_request(options_.access, con->get_resource(),
                       con->get_request_header("Authorization"), con->get_request_header("Host"),
                       con->get_request_header("Origin"));
}

void WebServer::Impl::on_http(Hdl hdl) {
  ++http_requests_;
  auto con = ws_.get_con_from_hdl(hdl);
  con->append_header("Cache-Control", "no-store");
  con->append_header("X-Content-Type-Options", "nosniff");
  const AccessDecision access = check(con);
  auto refuse = [&](websocketpp::http::status_code::value status, const std::string& why) {
    ++refused_;
    con->set_status(status);
    con->append_header("Content-Type", "text/plain; charset=utf-8");
    con->set_body(why + "\n");
  };
  if (access.status != 200) {
    refuse(static_cast<websocketpp::http::status_code::value>(access.status), access.message);
    return;
  }
  if (con->get_request().get_method() != "GET") {
    refuse(websocketpp::http::status_code::method_not_allowed, "GET only");
    return;
  }
  const auto file = static_file(con->get_resource());
  if (!file) {
    refuse(websocketpp::http::status_code::bad_request, "not a file name");
    return;
  }
  std::ifstream in(options_.static_dir + "/" + *file, std::ios::binary);
  std::ostringstream body;
  if (!in || !(body << in.rdbuf()) || body.str().size() > kMaxFileBytes) {
    refuse(websocketpp::http::status_code::not_found, "no such file: " + *file);
    return;
  }
  con->set_status(websocketpp::http::status_code::ok);
  con->append_header("Content-Type", content_type(*file));
  con->append_header("Content-Security-Policy",
                     "default-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data:");
  con->set_body(body.str());
}

bool WebServer::Impl::on_validate(Hdl hdl) {
  auto con = ws_.get_con_from_hdl(hdl);
  const AccessDecision access = check(con);
  std::lock_guard<std::mutex> lock(mutex_);
  if (access.status != 200) {
    ++refused_;
    spdlog::warn("refused a WebSocket from {}: {}", con->get_remote_endpoint(), access.message);
    con->set_status(static_cast<websocketpp::http::status_code::value>(access.status));
    con->set_body(access.message + "\n");
    return false;
  }
  if (stopping_ || clients_.size() >= options_.max_clients) {
    ++refused_;
    con->set_status(websocketpp::http::status_code::service_unavailable);
    con->set_body("too many clients\n");
    return false;
  }
  validated_token_[hdl] = access.has_token;
  return true;
}

void WebServer::Impl::on_open(Hdl hdl) {
  auto con = ws_.get_con_from_hdl(hdl);
  auto client = std::make_shared<Client>();
  client->hdl = hdl;
  client->remote = con->get_remote_endpoint();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    client->id = next_client_id_++;
    const auto v = validated_token_.find(hdl);
    client->has_token = v != validated_token_.end() && v->second;
    if (v != validated_token_.end()) validated_token_.erase(v);
    clients_[hdl] = client;
    by_id_[client->id] = client;
  }
  ++connections_;
  spdlog::info("page #{} connected from {} ({})", client->id, client->remote,
               client->has_token ? "with the token: may command" : "without the token: read only");
  if (on_open_) on_open_(client->id);
}

void WebServer::Impl::on_close(Hdl hdl) {
  std::shared_ptr<Client> client;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    validated_token_.erase(hdl);
    const auto it = clients_.find(hdl);
    if (it == clients_.end()) return;
    client = it->second;
    by_id_.erase(client->id);
    clients_.erase(it);
  }
  spdlog::info("page #{} ({}) left; {} messages dropped for it", client->id, client->remote,
               client->dropped);
}

void WebServer::Impl::enqueue(Client& client, const std::string& text,
                              std::vector<std::shared_ptr<Client>>& to_flush) {
  if (client.closing_since_ns != 0) return;
  if (client.queued_bytes + client.socket_bytes + text.size() > options_.client_queue_bytes) {
    if (client.full_since_ns == 0) {
      client.full_since_ns = clock::monotonic_ns();
      spdlog::warn("page #{} ({}) is not keeping up: its queue is full, new messages dropped",
                   client.id, client.remote);
    }
    ++client.dropped;
    ++dropped_;
    return;
  }
  client.full_since_ns = 0;
  client.queue.push_back(text);
  client.queued_bytes += text.size();
  if (!client.flush_posted) {
    client.flush_posted = true;
    to_flush.push_back(by_id_.at(client.id));
  }
}

void WebServer::Impl::send(std::uint64_t id, const std::string& text) {
  if (stopping_) return;
  std::vector<std::shared_ptr<Client>> to_flush;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = by_id_.find(id);
    if (it == by_id_.end()) return;
    enqueue(*it->second, text, to_flush);
  }
  for (auto& c : to_flush) asio::post(ws_.get_io_service(), [this, c] { flush(c); });
}

void WebServer::Impl::broadcast(const std::string& text) {
  if (stopping_) return;
  std::vector<std::shared_ptr<Client>> to_flush;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [id, client] : by_id_) enqueue(*client, text, to_flush);
  }
  for (auto& c : to_flush) asio::post(ws_.get_io_service(), [this, c] { flush(c); });
}

// On the I/O thread: queued messages into the socket while its buffer holds less than the
// client's bound; the rest waits for the next tick.
void WebServer::Impl::flush(const std::shared_ptr<Client>& client) {
  std::error_code ec;
  auto con = ws_.get_con_from_hdl(client->hdl, ec);
  if (ec) return;
  std::size_t buffered = con->get_buffered_amount();
  std::vector<std::string> messages;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    client->flush_posted = false;
    while (!client->queue.empty() && buffered < options_.client_queue_bytes) {
      buffered += client->queue.front().size();
      client->queued_bytes -= client->queue.front().size();
      messages.push_back(std::move(client->queue.front()));
      client->queue.pop_front();
    }
    client->socket_bytes = buffered;
  }
  for (const auto& m : messages) {
    ws_.send(client->hdl, m, websocketpp::frame::opcode::text, ec);
    if (ec) break;
  }
  buffered = con->get_buffered_amount();
  std::lock_guard<std::mutex> lock(mutex_);
  client->socket_bytes = buffered;
  // It read what a burst had piled up: only a queue that stays full makes a client slow.
  if (client->queue.empty() && buffered < options_.client_queue_bytes / 2)
    client->full_since_ns = 0;
}

void WebServer::Impl::schedule_tick() {
  tick_timer_->expires_after(kTick);
  tick_timer_->async_wait([this](const std::error_code& ec) {
    if (ec || stopping_) return;
    tick();
    schedule_tick();
  });
}

void WebServer::Impl::tick() {
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
        client->queue.clear();
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
    spdlog::warn("page #{} ({}) disconnected: its queue was full for {:.1f} s (not reading)",
                 client->id, client->remote, options_.slow_client_timeout_s);
    ws_.close(client->hdl, websocketpp::close::status::policy_violation, "not reading", ec);
  }
  for (auto& client : to_cut) {
    auto con = ws_.get_con_from_hdl(client->hdl, ec);
    if (!ec) con->get_raw_socket().close(ec);
  }
}

WebServerStats WebServer::Impl::stats() const {
  WebServerStats s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.clients = clients_.size();
  }
  s.connections = connections_;
  s.http_requests = http_requests_;
  s.refused = refused_;
  s.dropped = dropped_;
  s.slow_disconnects = slow_disconnects_;
  return s;
}

WebServer::WebServer(WebServerOptions options, MessageHandler on_message, OpenHandler on_open)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(on_message), std::move(on_open))) {
}
WebServer::~WebServer() = default;
std::uint16_t WebServer::port() const {
  return impl_->port();
}
void WebServer::send(std::uint64_t client, const std::string& text) {
  impl_->send(client, text);
}
void WebServer::broadcast(const std::string& text) {
  impl_->broadcast(text);
}
WebServerStats WebServer::stats() const {
  return impl_->stats();
}
void WebServer::stop() {
  impl_->stop();
}

}  // namespace cover::ground_station
