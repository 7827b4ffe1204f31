// services/websocket (websocket::Server) on its own: a real server on an ephemeral port and
// an independent client, the npm `ws` package (websocket_client.js, in Node processes).
#include "cover/websocket/server.hpp"

#include <dirent.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "recorder_support.hpp"  // find_node

namespace cover::websocket {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

constexpr const char* kProtocol = "cover.test";

// The threads of this process now.
std::size_t thread_count() {
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator("/proc/self/task")) {
    (void)entry;
    ++n;
  }
  return n;
}

// websocket_client.js connected to ws://127.0.0.1:PORT/PATH; its JSON lines read as needed.
class Client {
 public:
  Client(std::uint16_t port, const std::string& path, const json& options,
         const std::string& name) {
    process::SpawnOptions spawn;
    spawn.capture_stdout = true;
    spawn.log_file = test::scratch_path(name + ".stderr");
    spawn.extra_env = {"NODE_PATH=" + std::string(COVER_WS_NODE_MODULES)};
    child_ = std::make_unique<process::ChildProcess>(
        std::vector<std::string>{test::find_node(), COVER_WS_CLIENT,
                                 "ws://127.0.0.1:" + std::to_string(port) + path, options.dump()},
        spawn);
  }
  // The next line whose event is `event` (the others before it are kept in lines()); null
  // when none comes in time.
  json next(const std::string& event, std::chrono::milliseconds timeout = 10s) {
    const auto deadline = std::chrono::steady_clock::now() + test::scaled(timeout);
    while (std::chrono::steady_clock::now() < deadline) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      const auto line = child_->read_line(std::max(left, 1ms));
      if (!line) break;
      json parsed = json::parse(*line, nullptr, false);
      lines_.push_back(parsed);
      if (parsed.is_object() && parsed.value("event", "") == event) return parsed;
    }
    return nullptr;
  }
  const std::vector<json>& lines() const { return lines_; }
  process::ChildProcess& process() { return *child_; }

 private:
  std::unique_ptr<process::ChildProcess> child_;
  std::vector<json> lines_;
};

// A server whose handlers record what they see: each client by the path it opened, every
// message, every close. It selects kProtocol when offered and refuses the path /refuse.
class Recorded {
 public:
  explicit Recorded(ServerOptions options = small_options()) {
    Handlers h;
    h.validate = [](Request& handshake) {
      if (handshake.resource() == "/refuse") {
        handshake.set_status(403);
        handshake.set_body("not you\n");
        return false;
      }
      for (const auto& offered : handshake.offered_subprotocols()) {
        if (offered == kProtocol) handshake.select_subprotocol(kProtocol);
      }
      return true;
    };
    h.open = [this](ClientId client, const Request& handshake) {
      std::lock_guard<std::mutex> lock(mutex_);
      by_path_[handshake.resource()] = client;
      protocols_[client] = handshake.subprotocol();
    };
    h.message = [this](ClientId client, Opcode opcode, const std::string& payload) {
      std::lock_guard<std::mutex> lock(mutex_);
      messages_.push_back({client, opcode, payload});
    };
    h.close = [this](ClientId client) {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_.push_back(client);
    };
    server = std::make_unique<Server>(options, h);
  }

  static ServerOptions small_options() {
    ServerOptions o;
    o.port = 0;
    o.client_queue_bytes = 256 * 1024;
    o.slow_client_timeout_s = 0.5;
    o.max_message_bytes = 64 * 1024;
    return o;
  }

  // The id of the client that opened `path`, once it has.
  ClientId client(const std::string& path) {
    ClientId id = 0;
    EXPECT_TRUE(test::wait_until(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          const auto found = by_path_.find(path);
          if (found != by_path_.end()) id = found->second;
          return id != 0;
        },
        10s))
        << path << " never opened";
    return id;
  }
  std::string protocol(ClientId client) {
    std::lock_guard<std::mutex> lock(mutex_);
    return protocols_[client];
  }
  struct Message {
    ClientId client;
    Opcode opcode;
    std::string payload;
  };
  std::vector<Message> messages() {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }
  bool closed(ClientId client) {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::find(closed_.begin(), closed_.end(), client) != closed_.end();
  }

  std::unique_ptr<Server> server;

 private:
  std::mutex mutex_;
  std::map<std::string, ClientId> by_path_;
  std::map<ClientId, std::string> protocols_;
  std::vector<Message> messages_;
  std::vector<ClientId> closed_;
};

class WebSocketServer : public ::testing::Test {
 protected:
  void SetUp() override {
    if (test::find_node().empty()) GTEST_SKIP() << "node is not installed: these tests need Node";
    ASSERT_TRUE(fs::exists(fs::path(COVER_WS_NODE_MODULES) / "ws"))
        << "the `ws` package is missing: run scripts/setup (npm ci in tests/foxglove/peer)";
  }
};

TEST_F(WebSocketServer, HandshakeSelectsTheSubprotocolAndTextGoesBothWays) {
  Recorded served;
  ASSERT_NE(served.server->port(), 0);
  Client client(served.server->port(), "/chat", {{"protocols", {"other", kProtocol}}}, "chat");
  const json open = client.next("open", 30s);
  ASSERT_TRUE(open.is_object()) << "no open";
  EXPECT_EQ(open["protocol"], kProtocol);
  const ClientId id = served.client("/chat");
  EXPECT_EQ(served.protocol(id), kProtocol);

  // Server to client: a text as sent; the client answers "send:" with the rest.
  ASSERT_TRUE(served.server->send(id, "send:héllo from the client", Opcode::Text));
  const json echoed = client.next("message");
  ASSERT_TRUE(echoed.is_object());
  EXPECT_EQ(echoed["text"], "send:héllo from the client");
  ASSERT_TRUE(test::wait_until([&] { return !served.messages().empty(); }, 10s));
  const auto got = served.messages().front();
  EXPECT_EQ(got.client, id);
  EXPECT_EQ(got.opcode, Opcode::Text);
  EXPECT_EQ(got.payload, "héllo from the client");
  EXPECT_EQ(served.server->stats().clients, 1u);

  // A refused handshake gets the handler's status and body, and is counted.
  Client refused(served.server->port(), "/refuse", json::object(), "refused");
  const json answer = refused.next("refused");
  ASSERT_TRUE(answer.is_object());
  EXPECT_EQ(answer["status"], 403);
  EXPECT_EQ(answer["body"], "not you\n");
  EXPECT_EQ(served.server->stats().refused, 1u);
}

TEST_F(WebSocketServer, AClientThatStopsReadingIsDroppedWhileAnotherKeepsReceiving) {
  Recorded served;
  Client good(served.server->port(), "/good", json::object(), "good");
  Client stalled(served.server->port(), "/stalled", {{"stall", true}}, "stalled");
  ASSERT_TRUE(good.next("open", 30s).is_object());
  ASSERT_TRUE(stalled.next("open", 30s).is_object());
  const ClientId good_id = served.client("/good");
  const ClientId stalled_id = served.client("/stalled");

  // 16 KiB texts to the good one, paced by its backlog so that its queue (256 KiB) never
  // fills: it reads them as they come.
  const std::string bulk(16 * 1024, 'x');
  std::size_t sent_to_good = 0;
  auto send_to_good = [&] {
    ASSERT_TRUE(served.server->send(good_id, bulk, Opcode::Text));
    ++sent_to_good;
    ASSERT_TRUE(test::wait_until([&] { return served.server->backlog_bytes(good_id) < 64 * 1024; },
                                 10s, 1ms))
        << "the good client stopped reading";
  };
  // The same to both until the stalled one is dropped.
  const auto deadline = std::chrono::steady_clock::now() + test::scaled(60s);
  while (!served.closed(stalled_id) && std::chrono::steady_clock::now() < deadline) {
    served.server->send(stalled_id, bulk, Opcode::Text);
    send_to_good();
    if (HasFatalFailure()) return;
  }
  ASSERT_TRUE(served.closed(stalled_id)) << "the stalled client was never dropped";
  const ServerStats stats = served.server->stats();
  EXPECT_EQ(stats.slow_disconnects, 1u);
  EXPECT_GT(stats.dropped, 0u);  // the stalled client's, once its queue was full
  EXPECT_FALSE(served.closed(good_id));

  // The good one goes on: more after the drop, then every message it was sent has arrived.
  const std::size_t before_drop = sent_to_good;
  for (int i = 0; i < 50 && !HasFatalFailure(); ++i) send_to_good();
  ASSERT_EQ(sent_to_good, before_drop + 50);
  ASSERT_TRUE(served.server->send(good_id, "report?", Opcode::Text));
  const json report = good.next("report", 30s);
  ASSERT_TRUE(report.is_object()) << "no report";
  EXPECT_EQ(report["received"].get<std::size_t>(), sent_to_good);
  EXPECT_EQ(report["bytes"].get<std::size_t>(), sent_to_good * bulk.size());
  EXPECT_EQ(served.server->stats().clients, 1u);
}

TEST_F(WebSocketServer, AMessageBeyondTheLimitClosesItsConnectionUnread) {
  Recorded served;  // max_message_bytes 64 KiB
  Client client(served.server->port(), "/big", json::object(), "big");
  ASSERT_TRUE(client.next("open", 30s).is_object());
  const ClientId id = served.client("/big");
  // Just under the limit: taken.
  ASSERT_TRUE(served.server->send(id, "send-size:" + std::to_string(60 * 1024), Opcode::Text));
  ASSERT_TRUE(test::wait_until([&] { return served.messages().size() == 1; }, 10s));
  EXPECT_EQ(served.messages().front().payload.size(), 60u * 1024);
  // Beyond it: the connection is closed with 1009 (message too big), the message unseen.
  ASSERT_TRUE(served.server->send(id, "send-size:" + std::to_string(100 * 1024), Opcode::Text));
  const json close = client.next("close");
  ASSERT_TRUE(close.is_object()) << "not closed";
  EXPECT_EQ(close["code"], 1009);
  EXPECT_TRUE(test::wait_until([&] { return served.closed(id); }, 10s));
  EXPECT_EQ(served.messages().size(), 1u);
  EXPECT_EQ(client.process().wait(test::scaled(10s)), 0);
}

TEST_F(WebSocketServer, StoppingWithClientsConnectedClosesThemAndLeavesNoThread) {
  const std::size_t before = thread_count();
  auto served = std::make_unique<Recorded>();
  EXPECT_EQ(thread_count(), before + 1);  // its one I/O thread
  Client first(served->server->port(), "/first", json::object(), "first");
  Client second(served->server->port(), "/second", json::object(), "second");
  ASSERT_TRUE(first.next("open", 30s).is_object());
  ASSERT_TRUE(second.next("open", 30s).is_object());
  served->client("/first");
  served->client("/second");
  ASSERT_EQ(served->server->stats().clients, 2u);

  served->server->stop();
  EXPECT_EQ(thread_count(), before);
  for (Client* client : {&first, &second}) {
    const json close = client->next("close");
    ASSERT_TRUE(close.is_object()) << "not closed";
    EXPECT_EQ(close["code"], 1001);  // going away
    EXPECT_EQ(client->process().wait(test::scaled(10s)), 0);
  }
  EXPECT_FALSE(served->server->send(1, "late", Opcode::Text));
  served.reset();  // stop() again from the destructor: a no-op
  EXPECT_EQ(thread_count(), before);
}

}  // namespace
}  // namespace cover::websocket
