// The ground station's web server (cover_ground_station_web) in this process, its clients
// over bare sockets: the page's files, the WebSocket's access rules, an oversized message,
// a client that stops reading dropped while another keeps getting every message.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cover/ground_station/web_server.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/wait_until.hpp"
#include "raw_ws.hpp"

namespace gs = cover::ground_station;
using cover::test::RawWs;
using namespace std::chrono_literals;

namespace {

constexpr const char* kToken = "0123456789abcdef0123456789abcdef";

struct Served {
  explicit Served(bool token_required, std::size_t queue_bytes = 1024 * 1024,
                  double slow_timeout_s = 2.0) {
    const std::string dir = cover::test::scratch_path("web");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/index.html") << "<html>the page</html>";
    gs::WebServerOptions o;
    o.transport.port = 0;
    o.static_dir = dir;
    o.access = {kToken, token_required};
    o.transport.client_queue_bytes = queue_bytes;
    o.transport.slow_client_timeout_s = slow_timeout_s;
    server = std::make_unique<gs::WebServer>(
        o, [this](std::uint64_t client, bool has_token, const std::string& text) {
          std::lock_guard<std::mutex> lock(mutex);
          received.push_back(text);
          server->send(client, has_token ? "token:" + text : "read-only:" + text);
        });
  }
  std::uint16_t port() const { return server->port(); }
  std::mutex mutex;
  std::vector<std::string> received;
  std::unique_ptr<gs::WebServer> server;
};

}  // namespace

TEST(GroundStationServer, ServesThePageAndRefusesWhatIsNotAFile) {
  Served s(false);
  std::string response;
  EXPECT_EQ(RawWs().get(s.port(), "/", "", false, &response), 200);
  EXPECT_NE(response.find("the page"), std::string::npos);
  EXPECT_NE(response.find("Content-Security-Policy"), std::string::npos);
  EXPECT_EQ(RawWs().get(s.port(), "/missing.js", "", false), 404);
  EXPECT_EQ(RawWs().get(s.port(), "/../../etc/passwd", "", false), 400);
  EXPECT_EQ(RawWs().get(s.port(), "/", "Origin: http://evil.example\r\n", false), 403);
  EXPECT_EQ(RawWs().get(s.port(), "/?token=wrongwrongwrongwrong", "", false), 401);
}

TEST(GroundStationServer, NetworkBindNeedsTheTokenForPageAndWebSocket) {
  Served s(true);
  EXPECT_EQ(RawWs().get(s.port(), "/", "", false), 401);
  EXPECT_EQ(RawWs().get(s.port(), std::string("/?token=") + kToken, "", false), 200);
  EXPECT_EQ(RawWs().get(s.port(), "/ws", "", true), 401);
  RawWs ws;
  ASSERT_EQ(ws.get(s.port(), std::string("/ws?token=") + kToken, "", true), 101);
  ws.send_text("hello");
  EXPECT_EQ(ws.read_text(5000ms), "token:hello");
  EXPECT_EQ(s.server->stats().refused, 2u);
}

TEST(GroundStationServer, WebSocketFromAForeignOriginIsRefused) {
  Served s(false);
  EXPECT_EQ(RawWs().get(s.port(), "/ws", "Origin: http://evil.example\r\n", true), 403);
  RawWs same;
  ASSERT_EQ(same.get(s.port(), "/ws",
                     "Origin: http://127.0.0.1:" + std::to_string(s.port()) + "\r\n", true),
            101);
  same.send_text("x");
  // Without the token this page may read but not command: the handler is told.
  EXPECT_EQ(same.read_text(5000ms), "read-only:x");
}

TEST(GroundStationServer, OversizedMessageClosesOnlyThatConnection) {
  Served s(false);
  RawWs big, other;
  ASSERT_EQ(big.get(s.port(), "/ws", "", true), 101);
  ASSERT_EQ(other.get(s.port(), "/ws", "", true), 101);
  big.send_text(std::string(1024 * 1024, 'x'));
  EXPECT_EQ(big.read_text(5000ms), "");
  EXPECT_TRUE(big.closed());
  EXPECT_EQ(big.close_code(), 1009);  // message too big
  other.send_text("still here");
  EXPECT_EQ(other.read_text(5000ms), "read-only:still here");
  std::lock_guard<std::mutex> lock(s.mutex);
  EXPECT_EQ(s.received, std::vector<std::string>{"still here"});
}

TEST(GroundStationServer, ClientThatStopsReadingIsDroppedOthersKeepUp) {
  Served s(false, 64 * 1024, 0.5);
  RawWs slow, reader;
  slow.set_receive_buffer(4096);
  ASSERT_EQ(slow.get(s.port(), "/ws", "", true), 101);  // never reads from here on
  ASSERT_EQ(reader.get(s.port(), "/ws", "", true), 101);
  ASSERT_TRUE(cover::test::wait_until([&] { return s.server->stats().clients == 2; }, 5000ms));
  const std::string message(16 * 1024, 'm');
  std::atomic<int> read{0};
  std::atomic<bool> done{false};
  std::thread reading([&] {
    while (!done) {
      if (reader.read_text(100ms).size() == message.size()) ++read;
    }
  });
  int sent = 0;
  const bool dropped = cover::test::wait_until(
      [&] {
        s.server->broadcast(message);
        ++sent;
        return s.server->stats().slow_disconnects == 1;
      },
      30000ms, 10ms);
  // The reader still gets what is sent after the slow one is gone.
  const int before = read;
  int after = 0;
  EXPECT_TRUE(cover::test::wait_until(
      [&] {
        if (after < 20) {
          s.server->broadcast(message);
          ++after;
        }
        return read >= before + 20;
      },
      5000ms, 10ms));
  done = true;
  reading.join();
  EXPECT_TRUE(dropped) << sent << " messages sent";
  EXPECT_GT(s.server->stats().dropped, 0u);
  // Its socket, which takes no close frame either, is cut a second later.
  EXPECT_TRUE(cover::test::wait_until([&] { return s.server->stats().clients == 1; }, 5000ms));
}
