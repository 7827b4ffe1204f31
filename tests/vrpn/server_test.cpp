// The simulator's VRPN server (sim/mocap) against hand-written bytes, and the client
// (services/vrpn) against it over TCP: reports, pongs, the server going away and back.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <optional>

#include "cover/config/config_error.hpp"
#include "cover/sim/mocap/mocap_feed.hpp"
#include "cover/sim/mocap/mocap_server_params.hpp"
#include "cover/sim/mocap/vrpn_server.hpp"
#include "cover/test/shipped_params.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vrpn/tracker_client.hpp"
#include "spec_bytes.hpp"

namespace {

using namespace cover::test::vrpn_spec;
namespace mocap = cover::sim::mocap;
namespace vrpn = cover::vrpn;
using namespace std::chrono_literals;

using cover::test::scaled;
using cover::test::time_scale;

// A plain socket: the test reads exactly what the server writes.
class RawPeer {
 public:
  explicit RawPeer(std::uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  }
  ~RawPeer() { ::close(fd_); }
  void send(const Bytes& b) { ASSERT_EQ(::send(fd_, b.data(), b.size(), 0), (ssize_t)b.size()); }
  Bytes read(std::size_t n) {
    Bytes out(n);
    std::size_t have = 0;
    const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
    while (have < n && std::chrono::steady_clock::now() < deadline) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      const ssize_t got = ::recv(fd_, out.data() + have, n - have, 0);
      if (got <= 0) break;
      have += static_cast<std::size_t>(got);
    }
    out.resize(have);
    return out;
  }

 private:
  int fd_;
};

mocap::ServerOptions options(std::vector<std::string> bodies, std::uint16_t port = 0) {
  mocap::ServerOptions o;
  o.port = port;
  o.bodies = std::move(bodies);
  return o;
}

Bytes with_type_id(Bytes m, std::uint8_t id, std::size_t field_offset) {
  m[field_offset + 3] = id;
  return m;
}

TEST(VrpnServer, WritesTheSpecBytes) {
  mocap::VrpnServer server(options({"UAV_A"}));
  RawPeer peer(server.port());
  EXPECT_EQ(peer.read(24), cookie("07.38"));
  peer.send(cookie("07.35"));
  // Sender 0 "UAV_A", then the types: Pos_Quat is our type 0 (the example's 5, in the
  // sender field of the description).
  EXPECT_EQ(peer.read(sender_uav_a_id0().size()), sender_uav_a_id0());
  EXPECT_EQ(peer.read(type_pos_quat_id5().size()), with_type_id(type_pos_quat_id5(), 0, 12));
  ASSERT_TRUE(server.wait_for_clients(1, scaled(5s)));
  peer.read(3 * 56);  // Velocity (21 + 1 chars), ping and pong (22 + 1): 56 bytes each
  mocap::WirePose pose;
  pose.present = true;
  pose.position[0] = 1.0;
  pose.position[1] = 2.0;
  pose.position[2] = -0.5;
  pose.quaternion_xyzw[2] = 0.6;
  pose.quaternion_xyzw[3] = 0.8;
  server.send_frame(1'500'000'000, {pose});
  EXPECT_EQ(peer.read(88), with_type_id(pos_quat_sender0_type5(), 0, 16));
}

TEST(VrpnServer, RefusesAForeignCookie) {
  mocap::VrpnServer server(options({"UAV_A"}));
  RawPeer peer(server.port());
  peer.read(24);
  peer.send(text("GET / HTTP/1.1\r\nHost: a\r\n\r\n"));
  cover::test::wait_until([&] { return server.stats().dropped != 0; }, 5s, 1ms);
  EXPECT_EQ(server.stats().dropped, 1u);
  EXPECT_EQ(server.ready_clients(), 0u);
}

vrpn::ClientOptions client_options(std::uint16_t port, std::vector<std::string> bodies) {
  vrpn::ClientOptions o;
  o.port = port;
  o.session.bodies = std::move(bodies);
  o.backoff_min_s = 0.05;
  o.backoff_max_s = 0.2;
  o.silence_timeout_s = 1.0 * time_scale();
  return o;
}

// Polls the client until `done` or the deadline.
template <typename Done>
bool pump(vrpn::TrackerClient& client, std::vector<vrpn::TrackerReport>& reports, Done done,
          std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + scaled(timeout);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    client.poll(5ms, [&](const vrpn::TrackerReport& r) { reports.push_back(r); });
  }
  return true;
}

TEST(VrpnClientServer, SeveralBodiesOnOneConnectionWithPongs) {
  mocap::VrpnServer server(options({"ugv0", "ugv1", "uav0"}));
  vrpn::TrackerClient client(client_options(server.port(), {"uav0", "ugv1"}));
  std::vector<vrpn::TrackerReport> reports;
  ASSERT_TRUE(pump(
      client, reports, [&] { return client.connected(); }, 5s));
  ASSERT_TRUE(server.wait_for_clients(1, scaled(5s)));
  std::vector<mocap::WirePose> frame(3);
  for (int i = 0; i < 3; ++i) {
    frame[i].present = true;
    frame[i].position[0] = 10.0 + i;
  }
  for (int n = 0; n < 10; ++n) server.send_frame(2'000'000'000 + n * 10'000'000, frame);
  ASSERT_TRUE(pump(
      client, reports, [&] { return reports.size() >= 20; }, 5s));
  EXPECT_EQ(reports[0].body, 1);  // ugv1: the client's body 1
  EXPECT_EQ(reports[0].position[0], 11.0);
  EXPECT_EQ(reports[1].body, 0);  // uav0
  EXPECT_EQ(reports[1].position[0], 12.0);
  EXPECT_EQ(reports[19].time.to_ns(), 2'090'000'000);
  EXPECT_EQ(client.stats().session.untracked, 10u);  // ugv0
  ASSERT_TRUE(pump(
      client, reports, [&] { return server.stats().pongs > 0; }, 5s));
}

TEST(VrpnClientServer, ReconnectsWhenTheServerComesBack) {
  auto server = std::make_unique<mocap::VrpnServer>(options({"uav0"}));
  const std::uint16_t port = server->port();
  vrpn::TrackerClient client(client_options(port, {"uav0"}));
  std::vector<vrpn::TrackerReport> reports;
  ASSERT_TRUE(pump(
      client, reports, [&] { return client.connected(); }, 5s));
  server.reset();
  ASSERT_TRUE(pump(
      client, reports, [&] { return !client.connected(); }, 5s));
  EXPECT_EQ(client.stats().disconnects, 1u);
  // Away for a while: several attempts fail.
  const auto attempts = client.stats().connect_attempts;
  ASSERT_TRUE(pump(
      client, reports, [&] { return client.stats().connect_attempts >= attempts + 2; }, 5s));
  server = std::make_unique<mocap::VrpnServer>(options({"uav0"}, port));
  ASSERT_TRUE(pump(
      client, reports, [&] { return client.connected(); }, 5s));
  ASSERT_TRUE(server->wait_for_clients(1, scaled(5s)));
  mocap::WirePose pose;
  pose.present = true;
  server->send_frame(5'000'000'000, {pose});
  ASSERT_TRUE(pump(
      client, reports, [&] { return !reports.empty(); }, 5s));
  EXPECT_EQ(reports.back().time.to_ns(), 5'000'000'000);
  EXPECT_EQ(client.stats().connections, 2u);
}

// config/sim/mocap.yaml writes every field (MocapServerParams::fields) at its default.
TEST(MocapServerParams, ShippedFileHoldsEveryFieldAtItsDefault) {
  const std::string path = cover::config::default_config_dir() + "/sim/mocap.yaml";
  cover::test::expect_shipped_file_holds_defaults(mocap::MocapServerParams::load_file(path), path,
                                                  "mocap");
  const auto error = [](const std::string& yaml) {
    try {
      mocap::MocapServerParams::from_yaml(YAML::Load(yaml), "test.yaml");
    } catch (const cover::config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("mocap: {latency_s: 0.6}"), "mocap.latency_s: must be in [0, 0.5] s");
  EXPECT_NE(error("mocap: {up_axis: x}").find("test.yaml.mocap.up_axis: 'x' is not one of z, y"),
            std::string::npos);
  EXPECT_EQ(error("mocap: {ugv_prefix: uav}"),
            "mocap.uav_prefix: the prefixes must be non-empty and differ");
  EXPECT_NE(error("mocap: {rate: 100}").find("unknown key 'rate'"), std::string::npos);
}

TEST(MocapFeed, RateLatencyDropoutsAndFrames) {
  mocap::MocapServerParams p;
  p.rate_hz = 50.0;
  p.latency_s = 0.02;
  p.position_noise_m = 0.0;
  p.attitude_noise_rad = 0.0;
  p.dropout_probability = 0.0;
  mocap::MocapFeed feed(p, 1);
  mocap::BodyTruth truth;
  truth.position_m = {1.0, 2.0, 3.0};
  std::vector<mocap::MocapFrame> out;
  for (int tick = 0; tick <= 10; ++tick) feed.step(tick * 10'000'000LL, {truth}, out);
  // Captures at 0, 20, ..., 100 ms; released 20 ms later: 0..80 ms by t = 100 ms.
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0].capture_ns, 0);
  EXPECT_EQ(out[4].capture_ns, 80'000'000);
  EXPECT_EQ(out[4].poses[0].position[1], 2.0);

  // y up, millimetres: (x, y, z) -> (x, z, -y) * 1000; a yaw about world z becomes a
  // rotation about the y-up frame's y.
  truth.attitude = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  const mocap::WirePose w = mocap::to_wire(truth, "y", "mm");
  EXPECT_NEAR(w.position[0], 1000.0, 1e-9);
  EXPECT_NEAR(w.position[1], 3000.0, 1e-9);
  EXPECT_NEAR(w.position[2], -2000.0, 1e-9);
  EXPECT_NEAR(w.quaternion_xyzw[1], std::sin(0.25), 1e-12);
  EXPECT_NEAR(w.quaternion_xyzw[3], std::cos(0.25), 1e-12);

  p.dropout_probability = 0.5;
  p.latency_s = 0.0;
  mocap::MocapFeed lossy(p, 2);
  out.clear();
  for (int tick = 0; tick < 1000; ++tick) lossy.step(tick * 20'000'000LL, {truth, truth}, out);
  int missing = 0;
  for (const auto& f : out) missing += !f.poses[0].present + !f.poses[1].present;
  EXPECT_NEAR(missing / 2000.0, 0.5, 0.05);
}

}  // namespace
