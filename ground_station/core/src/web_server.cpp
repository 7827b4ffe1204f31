#include "cover/ground_station/web_server.hpp"

#include <spdlog/spdlog.h>

#include <atomic>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <utility>

#include "cover/websocket/server.hpp"

namespace cover::ground_station {
namespace {

using websocket::ClientId;
using websocket::Opcode;
using websocket::Request;

// The largest file served (the page's bundle is ~1 MB).
constexpr std::size_t kMaxFileBytes = 16 * 1024 * 1024;

AccessDecision check(const AccessPolicy& policy, const Request& request) {
  return check_request(policy, request.resource(), request.header("Authorization"),
                       request.header("Host"), request.header("Origin"));
}

}  // namespace

class WebServer::Impl {
 public:
  Impl(WebServerOptions options, MessageHandler on_message, OpenHandler on_open);
  ~Impl() { stop(); }

  std::uint16_t port() const { return transport_->port(); }
  void send(std::uint64_t client, const std::string& text) {
    transport_->send(client, text, Opcode::Text);
  }
  void broadcast(const std::string& text) { transport_->broadcast(text, Opcode::Text); }
  WebServerStats stats() const;
  void stop() { transport_->stop(); }

 private:
  websocket::Handlers handlers();
  void on_http(Request& request);
  bool on_validate(Request& handshake);
  void on_open(ClientId client, const Request& handshake);
  void on_close(ClientId client);
  void on_message(ClientId client, Opcode opcode, const std::string& text);
  void refuse(Request& request, int status, const std::string& why);

  WebServerOptions options_;
  MessageHandler on_message_;
  OpenHandler on_open_;

  mutable std::mutex mutex_;
  std::map<ClientId, bool> has_token_;  // the page's WebSocket was opened with the token

  std::atomic<std::uint64_t> http_requests_{0};
  std::atomic<std::uint64_t> http_refused_{0};
  // Last: its I/O thread calls the handlers above, so it is made after them and goes first.
  std::unique_ptr<websocket::Server> transport_;
};

WebServer::Impl::Impl(WebServerOptions options, MessageHandler message_handler,
                      OpenHandler open_handler)
    : options_(std::move(options)),
      on_message_(std::move(message_handler)),
      on_open_(std::move(open_handler)) {
  transport_ = std::make_unique<websocket::Server>(options_.transport, handlers());
}

websocket::Handlers WebServer::Impl::handlers() {
  websocket::Handlers h;
  h.http = [this](Request& request) { on_http(request); };
  h.validate = [this](Request& handshake) { return on_validate(handshake); };
  h.open = [this](ClientId c, const Request& handshake) { on_open(c, handshake); };
  h.close = [this](ClientId c) { on_close(c); };
  h.message = [this](ClientId c, Opcode opcode, const std::string& text) {
    on_message(c, opcode, text);
  };
  return h;
}

void WebServer::Impl::refuse(Request& request, int status, const std::string& why) {
  ++http_refused_;
  request.set_status(status);
  request.append_header("Content-Type", "text/plain; charset=utf-8");
  request.set_body(why + "\n");
}

void WebServer::Impl::on_http(Request& request) {
  ++http_requests_;
  request.append_header("Cache-Control", "no-store");
  request.append_header("X-Content-Type-Options", "nosniff");
  const AccessDecision access = check(options_.access, request);
  if (access.status != 200) return refuse(request, access.status, access.message);
  if (request.method() != "GET") return refuse(request, 405, "GET only");
  const auto file = static_file(request.resource());
  if (!file) return refuse(request, 400, "not a file name");
  std::ifstream in(options_.static_dir + "/" + *file, std::ios::binary);
  std::ostringstream body;
  if (!in || !(body << in.rdbuf()) || body.str().size() > kMaxFileBytes) {
    return refuse(request, 404, "no such file: " + *file);
  }
  request.set_status(200);
  request.append_header("Content-Type", content_type(*file));
  request.append_header(
      "Content-Security-Policy",
      "default-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data:");
  request.set_body(body.str());
}

bool WebServer::Impl::on_validate(Request& handshake) {
  const AccessDecision access = check(options_.access, handshake);
  if (access.status == 200) return true;
  spdlog::warn("refused a WebSocket from {}: {}", handshake.remote(), access.message);
  handshake.set_status(access.status);
  handshake.set_body(access.message + "\n");
  return false;
}

void WebServer::Impl::on_open(ClientId client, const Request& handshake) {
  const bool has_token = check(options_.access, handshake).has_token;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    has_token_[client] = has_token;
  }
  spdlog::info("page #{} connected from {} ({})", client, handshake.remote(),
               has_token ? "with the token: may command" : "without the token: read only");
  if (on_open_) on_open_(client);
}

void WebServer::Impl::on_close(ClientId client) {
  std::lock_guard<std::mutex> lock(mutex_);
  has_token_.erase(client);
}

void WebServer::Impl::on_message(ClientId client, Opcode opcode, const std::string& text) {
  if (opcode != Opcode::Text) return;
  bool has_token = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = has_token_.find(client);
    if (it == has_token_.end()) return;
    has_token = it->second;
  }
  on_message_(client, has_token, text);
}

WebServerStats WebServer::Impl::stats() const {
  const websocket::ServerStats transport = transport_->stats();
  WebServerStats s;
  s.clients = transport.clients;
  s.connections = transport.connections;
  s.http_requests = http_requests_;
  s.refused = http_refused_ + transport.refused;
  s.dropped = transport.dropped;
  s.slow_disconnects = transport.slow_disconnects;
  return s;
}

websocket::ServerOptions default_transport() {
  websocket::ServerOptions transport;
  transport.log_name = "ground station server";
  transport.client_noun = "page";
  transport.address = "127.0.0.1";
  transport.port = 8080;
  transport.client_queue_bytes = 1024 * 1024;
  transport.slow_client_timeout_s = 2.0;
  transport.max_clients = 16;
  transport.max_message_bytes = 256 * 1024;
  return transport;
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
