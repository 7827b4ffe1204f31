// cover-mocap-relay as a process against the simulator's VRPN server (sim/mocap, run by
// the test): the scripted motion within the accuracy, a body lost for 0.3 s, the
// server gone and back, garbage from the server. DDS domains 111-119.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/sim/mocap/mocap_feed.hpp"
#include "cover/sim/mocap/vrpn_server.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "process_support.hpp"
#include "scripted_motion.hpp"
#include "spec_bytes.hpp"

namespace {

using namespace std::chrono_literals;
namespace mocap = cover::sim::mocap;
namespace motion = cover::test::mocap_motion;
using cover::process::ChildProcess;

using cover::test::read_text;
using cover::test::scaled;
using cover::test::time_scale;
bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
  return cover::test::wait_until(done, timeout, 2ms);
}
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

struct Sample {
  cover::msg::RelativeState state;
  std::int64_t received_mono_ns;
};

mocap::WirePose wire(const motion::Pose& p) {
  mocap::WirePose w;
  w.present = true;
  for (int i = 0; i < 3; ++i) w.position[i] = p.position_m[i];
  w.quaternion_xyzw[0] = p.attitude.x();
  w.quaternion_xyzw[1] = p.attitude.y();
  w.quaternion_xyzw[2] = p.attitude.z();
  w.quaternion_xyzw[3] = p.attitude.w();
  return w;
}

// The relay of uav0 ("UAV_A") in ugv0 ("Truck_2"), the test's reader of cover/uav/0/rel/0.
class RelayRun {
 public:
  explicit RelayRun(std::uint16_t port, const std::string& frame = "")
      : claim_(cover::dds::DomainClaim::claim_any(111, 119)),
        config_(cover::test::scratch_path("mocap.yaml")),
        log_(cover::test::scratch_path("relay.log")),
        participant_(options(claim_.domain())) {
    std::ofstream(config_) << "mocap:\n  server: \"127.0.0.1:" << port
                           << "\"\n  time_source: server\n  backoff_max_s: 0.3\n"
                           << frame << "  bodies: {uav0: UAV_A, ugv0: Truck_2}\n";
    reader_ = participant_.make_reader(cover::dds::topics::relative_state(0, 0),
                                       [this](const cover::msg::RelativeState& m) {
                                         std::lock_guard<std::mutex> lock(mutex_);
                                         samples_.push_back({m, cover::clock::monotonic_ns()});
                                       });
    cover::process::SpawnOptions spawn;
    spawn.extra_env = {"COVER_DDS=fastdds", "COVER_DDS_DOMAIN=" + std::to_string(claim_.domain())};
    spawn.log_file = log_;
    relay_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{cover::test::bin("cover-mocap-relay"), "--config", config_},
        spawn);
  }
  ~RelayRun() {
    if (relay_) relay_->terminate(scaled(10s), SIGINT);
  }

  bool matched() { return reader_.wait_for_writers(1, scaled(20s)); }
  // Whether a sample stamped `stamp_ns` or later arrived (valid ones only if asked): the
  // topic is best effort, so not necessarily the last one sent.
  bool reached(std::int64_t stamp_ns, bool valid_only = false) {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::any_of(samples_.begin(), samples_.end(), [&](const Sample& s) {
      return s.state.stamp_ns >= stamp_ns && (s.state.valid || !valid_only);
    });
  }
  std::vector<Sample> samples() {
    std::lock_guard<std::mutex> lock(mutex_);
    return samples_;
  }
  std::string log() const { return read_text(log_); }
  ChildProcess& relay() { return *relay_; }
  int stop() {
    const int code = relay_->terminate(scaled(10s), SIGINT);
    relay_.reset();
    return code;
  }

 private:
  static cover::dds::ParticipantOptions options(int domain) {
    cover::dds::ParticipantOptions o;
    o.vendor = cover::dds::Vendor::FastDds;
    o.domain_id = domain;
    return o;
  }
  cover::dds::DomainClaim claim_;
  std::string config_;
  std::string log_;
  cover::dds::Participant participant_;
  std::mutex mutex_;
  std::vector<Sample> samples_;
  cover::dds::Reader<cover::msg::RelativeState> reader_;
  std::unique_ptr<ChildProcess> relay_;
};

mocap::ServerOptions server_options(std::uint16_t port = 0) {
  mocap::ServerOptions o;
  o.port = port;
  o.bodies = {"Truck_2", "UAV_A"};
  return o;
}

// Streams the scripted motion at 100 Hz of wall time over server time [t0, t1); `uav_present`
// decides per frame; `up_axis` / `units`: the server's frame. Returns each frame's send
// time by its stamp.
std::map<std::int64_t, std::int64_t> stream(
    mocap::VrpnServer& server, double t0, double t1,
    const std::function<bool(double)>& uav_present = [](double) { return true; },
    const std::string& up_axis = "z", const std::string& units = "m") {
  std::map<std::int64_t, std::int64_t> sent;
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; t0 + i * 0.01 < t1 - 1e-9; ++i) {
    const double t = t0 + i * 0.01;
    std::vector<mocap::WirePose> frame{wire(motion::ugv(t)), wire(motion::uav(t))};
    if (up_axis != "z" || units != "m") {
      const motion::Pose poses[2] = {motion::ugv(t), motion::uav(t)};
      for (int i = 0; i < 2; ++i) {
        frame[i] = mocap::to_wire({poses[i].position_m, poses[i].attitude}, up_axis, units);
      }
    }
    frame[1].present = uav_present(t);
    const std::int64_t stamp = std::llround(t * 1e9);
    sent[stamp] = cover::clock::monotonic_ns();
    server.send_frame(stamp, frame);
    next += 10ms;
    std::this_thread::sleep_until(next);  // the mocap system's pace, not a synchronisation
  }
  return sent;
}

std::uint16_t free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(fd);
  return ntohs(a.sin_port);
}

TEST(MocapRelayProcess, ScriptedMotionWithinTheAccuracyTargets) {
  mocap::VrpnServer server(server_options());
  RelayRun run(server.port());
  ASSERT_TRUE(run.matched());
  ASSERT_TRUE(server.wait_for_clients(1, scaled(20s)));
  const auto sent = stream(server, 1.0, 4.0);
  ASSERT_TRUE(wait_until([&] { return run.reached(sent.rbegin()->first - 100'000'000); }, 5s));
  wait_until([&] { return run.reached(sent.rbegin()->first); }, 500ms);  // the last, if it comes
  std::vector<double> position, velocity, latency_ms;
  int valid = 0;
  for (const Sample& s : run.samples()) {
    const double t = static_cast<double>(s.state.stamp_ns) * 1e-9;
    const auto send = sent.find(s.state.stamp_ns);
    ASSERT_NE(send, sent.end()) << "a stamp no frame had: " << s.state.stamp_ns;
    latency_ms.push_back(static_cast<double>(s.received_mono_ns - send->second) * 1e-6);
    if (t < 1.1) continue;  // the filters' warm-up
    ASSERT_TRUE(s.state.valid) << t;
    ++valid;
    const auto& p = s.state.position_m;
    const auto& v = s.state.velocity_m_s;
    position.push_back((Eigen::Vector3d(p.x, p.y, p.z) - motion::uav_in_ugv(t)).norm());
    velocity.push_back((Eigen::Vector3d(v.x, v.y, v.z) - motion::uav_velocity_in_ugv(t)).norm());
  }
  EXPECT_GE(valid, 270);  // of 290: a best-effort sample may be lost under load
  std::printf(
      "relay vs scripted motion: position p50 %.3f p99 %.3f mm, velocity p50 %.1f p99 %.1f mm/s, "
      "VRPN send -> DDS sample p50 %.3f p99 %.3f ms (%zu samples)\n",
      percentile(position, 0.5) * 1e3, percentile(position, 0.99) * 1e3,
      percentile(velocity, 0.5) * 1e3, percentile(velocity, 0.99) * 1e3,
      percentile(latency_ms, 0.5), percentile(latency_ms, 0.99), latency_ms.size());
  EXPECT_LE(percentile(position, 0.99), 0.005);
  EXPECT_LE(percentile(velocity, 0.99), 0.05);
  // The 2 ms p99 is the relay's own (socket to written, in its log); here TCP and
  // DDS delivery are included, on a machine CI loads: both bounds are loose (measured on
  // the 2-core VM: p50 0.3 ms, p99 0.7-16 ms).
  EXPECT_LE(percentile(latency_ms, 0.5), 5.0 * time_scale());
  EXPECT_LE(percentile(latency_ms, 0.99), 50.0 * time_scale());
  EXPECT_EQ(run.stop(), 0);
}

// A y-up server in millimetres (OptiTrack Motive's defaults, some Vicon setups): the relay
// configured so gives the same states. The server's conversion (sim/mocap) and the relay's
// (mocap/core) are separate code.
TEST(MocapRelayProcess, AYUpServerInMillimetresGivesTheSameStates) {
  mocap::VrpnServer server(server_options());
  RelayRun run(server.port(), "  up_axis: y\n  units: mm\n");
  ASSERT_TRUE(run.matched());
  ASSERT_TRUE(server.wait_for_clients(1, scaled(20s)));
  stream(
      server, 1.0, 1.6, [](double) { return true; }, "y", "mm");
  ASSERT_TRUE(wait_until([&] { return run.reached(1'500'000'000); }, 5s));
  int compared = 0;
  for (const Sample& s : run.samples()) {
    const double t = static_cast<double>(s.state.stamp_ns) * 1e-9;
    if (t < 1.1) continue;
    ASSERT_TRUE(s.state.valid);
    const auto& p = s.state.position_m;
    const auto& q = s.state.attitude;
    EXPECT_LE((Eigen::Vector3d(p.x, p.y, p.z) - motion::uav_in_ugv(t)).norm(), 0.001) << t;
    EXPECT_LE(
        Eigen::Quaterniond(q.w, q.x, q.y, q.z).angularDistance(motion::uav_attitude_in_ugv(t)),
        0.001)
        << t;
    ++compared;
  }
  EXPECT_GE(compared, 40);
  EXPECT_EQ(run.stop(), 0);
}

TEST(MocapRelayProcess, ABodyGoneForThreeTenthsIsInvalidThenValidAgain) {
  mocap::VrpnServer server(server_options());
  RelayRun run(server.port());
  ASSERT_TRUE(run.matched());
  ASSERT_TRUE(server.wait_for_clients(1, scaled(20s)));
  stream(server, 1.0, 2.2, [](double t) { return !(t >= 1.495 && t < 1.795); });
  ASSERT_TRUE(wait_until([&] { return run.reached(2'100'000'000); }, 5s));
  int invalid_in_gap = 0, valid_after = 0, invalid_after = 0;
  for (const Sample& s : run.samples()) {
    const double t = static_cast<double>(s.state.stamp_ns) * 1e-9;
    EXPECT_TRUE(std::isfinite(s.state.position_m.x)) << t;
    if (t >= 1.56 && t < 1.79) invalid_in_gap += !s.state.valid;
    if (t >= 1.9) (s.state.valid ? valid_after : invalid_after)++;
  }
  EXPECT_GE(invalid_in_gap, 20);  // every frame of the gap past lost_after_s
  EXPECT_GE(valid_after, 20);
  EXPECT_EQ(invalid_after, 0);
  const std::string log = run.log();
  EXPECT_NE(log.find("uav0 in ugv0: invalid at t = 1.5"), std::string::npos) << log;
  EXPECT_NE(log.find("not seen for"), std::string::npos) << log;
  EXPECT_NE(log.find("uav0 in ugv0: valid at t = 1.8"), std::string::npos) << log;
  EXPECT_EQ(run.stop(), 0);
}

TEST(MocapRelayProcess, ReconnectsWhenTheServerIsKilledAndRestarted) {
  auto server = std::make_unique<mocap::VrpnServer>(server_options());
  const std::uint16_t port = server->port();
  RelayRun run(port);
  ASSERT_TRUE(run.matched());
  ASSERT_TRUE(server->wait_for_clients(1, scaled(20s)));
  stream(*server, 1.0, 1.3);
  server.reset();  // the mocap host goes away
  ASSERT_TRUE(
      wait_until([&] { return run.log().find("connection lost") != std::string::npos; }, 5s));
  server = std::make_unique<mocap::VrpnServer>(server_options(port));
  ASSERT_TRUE(server->wait_for_clients(1, scaled(10s)));
  stream(*server, 5.0, 5.5);
  ASSERT_TRUE(wait_until([&] { return run.reached(5'300'000'000, true); }, 5s));
  EXPECT_FALSE(run.relay().wait(0ms).has_value()) << "the relay restarted or died";
  EXPECT_EQ(run.stop(), 0);
}

// A server that sends a cookie, then bytes out of step; the relay must drop it, count it
// and come back to the real server on the same port.
TEST(MocapRelayProcess, GarbageFromTheServerIsCountedNotACrash) {
  namespace spec = cover::test::vrpn_spec;
  const std::uint16_t port = free_tcp_port();
  // Close-on-exec: the relay started below must not inherit the port.
  const int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(listener, 1), 0);
  RelayRun run(port);
  pollfd p{listener, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, static_cast<int>(scaled(20s).count())), 1);
  const int peer = ::accept(listener, nullptr, nullptr);
  ASSERT_GE(peer, 0);
  spec::Bytes bad =
      spec::cat({spec::cookie(), spec::sender_uav_a_id0(), spec::type_pos_quat_id5(),
                 spec::pos_quat_sender0_type5(), spec::hex("7fffffff 00000000 deadbeef")});
  for (int i = 0; i < 64; ++i) bad.push_back(static_cast<std::uint8_t>(i * 37));
  ASSERT_EQ(::send(peer, bad.data(), bad.size(), MSG_NOSIGNAL), static_cast<ssize_t>(bad.size()));
  ASSERT_TRUE(wait_until([&] { return run.log().find("out of step") != std::string::npos; }, 5s))
      << run.log();
  ::close(peer);
  ::close(listener);
  // The relay is knocking on the port meanwhile: binding it may fail for a moment.
  std::unique_ptr<mocap::VrpnServer> server;
  ASSERT_TRUE(wait_until(
      [&] {
        try {
          server = std::make_unique<mocap::VrpnServer>(server_options(port));
        } catch (const std::runtime_error&) {
        }
        return server != nullptr;
      },
      5s));
  ASSERT_TRUE(run.matched());
  ASSERT_TRUE(server->wait_for_clients(1, scaled(10s)));
  stream(*server, 2.0, 2.3);
  ASSERT_TRUE(wait_until([&] { return run.reached(2'150'000'000); }, 5s));
  EXPECT_FALSE(run.relay().wait(0ms).has_value());
  EXPECT_EQ(run.stop(), 0);
  EXPECT_NE(run.log().find("1 bad lengths"), std::string::npos) << run.log();
}

}  // namespace
