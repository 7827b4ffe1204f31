// cover-sim's MAVLink side as real processes on free UDP ports: a test-side MAVLink client
// (our codec on a UDP socket) meets the simulated autopilot, and cover-ugv-agent reads the
// UGV IMU that cover-sim serves as a rover autopilot and publishes it on DDS.
#include <gtest/gtest.h>
#include <signal.h>

#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "test_support.hpp"

namespace {

using cover::process::ChildProcess;
using cover::sim::fc::test::free_port_base;
using cover::sim::fc::test::scaled;
using cover::sim::fc::test::wait_until;
namespace mav = cover::mavlink;
using namespace std::chrono_literals;

std::string bin(const std::string& name) {
  return std::string(COVER_BIN_DIR) + "/" + name;
}

cover::process::SpawnOptions on_domain(int domain, const std::string& log) {
  cover::process::SpawnOptions options;
  options.extra_env = {"COVER_DDS=fastdds", "COVER_DDS_DOMAIN=" + std::to_string(domain)};
  options.log_file = cover::test::scratch_path(log);
  return options;
}

std::string run_id(const std::string& tag) {
  return tag + "_" + std::to_string(::getpid());
}

// A ground station on the autopilot's peer port: what a bridge with udpin:// would be.
class MavlinkClient {
 public:
  explicit MavlinkClient(std::uint16_t listen_port)
      : link_(mav::make_link(
            mav::ConnectionUrl::parse("udpin://127.0.0.1:" + std::to_string(listen_port)))) {
    EXPECT_TRUE(link_->open()) << link_->last_error();
  }

  // Reads frames until `match` holds for one (returned) or `timeout` passes.
  template <typename M>
  std::optional<M> wait_for(std::chrono::milliseconds timeout,
                            const std::function<bool(const M&)>& match = {}) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::array<std::uint8_t, 2048> buffer{};
    std::optional<M> found;
    while (!found && std::chrono::steady_clock::now() < deadline) {
      const std::size_t n = link_->read(buffer.data(), buffer.size(), 50ms);
      parser_.feed(buffer.data(), n, [&](const mav::Frame& frame) {
        last_system_ = frame.system_id;
        if (found) return;
        if (auto m = mav::decode<M>(frame); m && (!match || match(*m))) found = m;
      });
    }
    return found;
  }

  template <typename M>
  void send(const M& message) {
    const auto frame = encoder_.encode(message);
    ASSERT_TRUE(link_->write(frame.bytes.data(), frame.size)) << link_->last_error();
  }
  // Reads what is there: a socket left unread overflows and drops what comes next.
  void drain() {
    std::array<std::uint8_t, 2048> buffer{};
    while (const std::size_t n = link_->read(buffer.data(), buffer.size(), 0ms)) {
      parser_.feed(buffer.data(), n, [](const mav::Frame&) {});
    }
  }
  std::uint8_t last_system() const { return last_system_; }
  const mav::ParserStats& stats() const { return parser_.stats(); }

 private:
  std::unique_ptr<mav::Link> link_;
  mav::StreamParser parser_;
  mav::Encoder encoder_{245, mav::mav_comp::kOnboardComputer};
  std::uint8_t last_system_ = 0;
};

struct Profile {
  const char* name;
  std::uint8_t autopilot;
  std::uint32_t start_mode;
  std::uint32_t offboard_main;
  std::uint8_t refused;
};

void heartbeats_and_a_refused_offboard(const Profile& profile) {
  auto domain = cover::dds::DomainClaim::claim_any(230, 232);
  const std::uint16_t bind_base = free_port_base(1);
  const std::uint16_t peer_base = free_port_base(1);
  MavlinkClient client(peer_base);
  ChildProcess sim({bin("cover-sim"), "--fc", profile.name, "--clock", "realtime", "--standing",
                    "--run-id", run_id(profile.name), "--fc-bind-port-base",
                    std::to_string(bind_base), "--fc-peer-port-base", std::to_string(peer_base)},
                   on_domain(domain.domain(), std::string("sim_") + profile.name + ".log"));

  // Heartbeats come while the simulator still waits for its UAV agent.
  const auto heartbeat = client.wait_for<mav::Heartbeat>(scaled(10s));
  ASSERT_TRUE(heartbeat);
  EXPECT_EQ(client.last_system(), 1);  // system_id_base + UAV 0
  EXPECT_EQ(heartbeat->autopilot, profile.autopilot);
  EXPECT_EQ(heartbeat->type, mav::mav_type::kQuadrotor);
  EXPECT_EQ(heartbeat->custom_mode, profile.start_mode);
  EXPECT_EQ(heartbeat->base_mode & mav::mav_mode_flag::kSafetyArmed, 0);

  mav::CommandLong offboard;
  offboard.command = mav::mav_cmd::kDoSetMode;
  offboard.param[0] = mav::mav_mode_flag::kCustomModeEnabled;
  offboard.param[1] = static_cast<float>(profile.offboard_main);
  offboard.target_system = client.last_system();
  offboard.target_component = 1;
  client.send(offboard);
  const auto ack = client.wait_for<mav::CommandAck>(scaled(3s));
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->command, mav::mav_cmd::kDoSetMode);
  EXPECT_EQ(ack->result, profile.refused);
  EXPECT_EQ(ack->target_system, 245);
  EXPECT_EQ(client.stats().errors(), 0u);

  EXPECT_EQ(sim.terminate(scaled(10s), SIGINT), 0);  // a standing world ends by being stopped
}

TEST(SimFcProcess, Px4HeartbeatsAndRefusesOffboardWithoutASetpointStream) {
  heartbeats_and_a_refused_offboard(
      {"px4", mav::mav_autopilot::kPx4, mav::px4_mode::custom_mode(mav::px4_mode::kMainManual),
       mav::px4_mode::kMainOffboard, mav::mav_result::kTemporarilyRejected});
}

TEST(SimFcProcess, ArduPilotHeartbeatsAndRefusesGuidedNoGpsWithoutASetpointStream) {
  heartbeats_and_a_refused_offboard({"ardupilot", mav::mav_autopilot::kArdupilotMega,
                                     mav::copter_mode::kStabilize, mav::copter_mode::kGuidedNoGps,
                                     mav::mav_result::kFailed});
}

// The UAV side of a lockstep run, played by the test: it answers each tick with a trace on
// DDS (as the UAV agent) and a SET_ATTITUDE_TARGET on MAVLink (as the bridge).
class LockstepCompanion {
 public:
  LockstepCompanion(int domain, std::uint16_t listen_port)
      : participant_(options(domain)), client_(listen_port) {
    clock_ = participant_.make_reader(cover::dds::topics::sim_clock(),
                                      [this](const cover::msg::SimClock& tick) {
                                        std::lock_guard<std::mutex> lock(mutex_);
                                        ticks_.push_back(tick.stamp_ns);
                                      });
    trace_ = participant_.make_writer(cover::dds::topics::uav_trace(0));
  }

  // The next tick the simulator published (a new one or the last one again).
  std::optional<std::int64_t> next_tick(std::chrono::milliseconds timeout) {
    std::optional<std::int64_t> tick;
    wait_until(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          if (ticks_.empty()) return false;
          tick = ticks_.front();
          ticks_.erase(ticks_.begin());
          return true;
        },
        timeout);
    return tick;
  }

  // Answers tick `stamp_ns`: the trace, then a setpoint named `time_boot_ms`.
  void answer(std::int64_t stamp_ns, std::uint32_t time_boot_ms, float thrust) {
    cover::msg::ControlTrace trace;
    trace.uav_id = 0;
    trace.stamp_ns = stamp_ns;
    trace_.write(trace);
    mav::SetAttitudeTarget setpoint;
    setpoint.time_boot_ms = time_boot_ms;
    setpoint.thrust = thrust;
    setpoint.target_system = 1;
    setpoint.target_component = 1;
    setpoint.type_mask = mav::attitude_target_typemask::kIgnoreAttitude;
    client_.send(setpoint);
  }

  MavlinkClient& mavlink() { return client_; }

 private:
  static cover::dds::ParticipantOptions options(int domain) {
    cover::dds::ParticipantOptions o;
    o.vendor = cover::dds::Vendor::FastDds;
    o.domain_id = domain;
    return o;
  }
  cover::dds::Participant participant_;
  MavlinkClient client_;
  std::mutex mutex_;
  std::vector<std::int64_t> ticks_;
  cover::dds::Reader<cover::msg::SimClock> clock_;
  cover::dds::Writer<cover::msg::ControlTrace> trace_;
};

TEST(SimFcProcess, LockstepTickWaitsForTheSetpointNamingIt) {
  auto domain = cover::dds::DomainClaim::claim_any(230, 232);
  const std::uint16_t bind_base = free_port_base(1);
  const std::uint16_t peer_base = free_port_base(1);
  LockstepCompanion companion(domain.domain(), peer_base);
  ChildProcess sim({bin("cover-sim"), "--fc", "px4", "--clock", "lockstep", "--standing",
                    "--run-id", run_id("lockstep"), "--fc-bind-port-base",
                    std::to_string(bind_base), "--fc-peer-port-base", std::to_string(peer_base)},
                   on_domain(domain.domain(), "sim.log"));
  ASSERT_TRUE(companion.mavlink().wait_for<mav::Heartbeat>(scaled(20s)));

  // 150 ticks answered, each by the setpoint naming it: the simulator steps one at a time.
  std::int64_t expected_ns = 0;
  int answered = 0;
  while (answered < 150) {
    const auto tick = companion.next_tick(20s);
    ASSERT_TRUE(tick) << "no tick after " << answered;
    if (*tick < expected_ns) continue;  // a tick published again before our answer arrived
    ASSERT_EQ(*tick, expected_ns);
    companion.answer(*tick, static_cast<std::uint32_t>(*tick / 1'000'000), 0.0F);
    companion.mavlink().drain();
    expected_ns += 10'000'000;
    ++answered;
  }
  // A setpoint naming another time does not answer the tick: it is published again.
  const auto tick = companion.next_tick(5s);
  ASSERT_EQ(tick, std::optional<std::int64_t>(expected_ns));
  companion.answer(*tick, static_cast<std::uint32_t>(*tick / 1'000'000) - 10, 0.0F);
  const auto again = companion.next_tick(5s);
  EXPECT_EQ(again, tick);
  companion.answer(*tick, static_cast<std::uint32_t>(*tick / 1'000'000), 0.0F);
  std::optional<std::int64_t> next;
  do {
    next = companion.next_tick(5s);
  } while (next && *next == *tick);
  EXPECT_EQ(next, std::optional<std::int64_t>(*tick + 10'000'000));

  // 1.5 s of simulated time at 100 Hz is a setpoint stream: OFFBOARD is granted.
  mav::CommandLong offboard;
  offboard.command = mav::mav_cmd::kDoSetMode;
  offboard.param[0] = 1.0F;
  offboard.param[1] = mav::px4_mode::kMainOffboard;
  offboard.target_system = 1;
  offboard.target_component = 1;
  companion.mavlink().send(offboard);
  const auto ack = companion.mavlink().wait_for<mav::CommandAck>(scaled(5s));
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->result, mav::mav_result::kAccepted);
  EXPECT_EQ(sim.terminate(scaled(10s), SIGINT), 0);
}

// cover/ugv/<k>/imu and /status as a test participant sees them.
class UgvObserver {
 public:
  UgvObserver(int domain, std::uint32_t ugv) : participant_(options(domain)) {
    imu_ = participant_.make_reader(cover::dds::topics::ugv_imu(ugv),
                                    [this](const cover::msg::UgvImu& m) {
                                      std::lock_guard<std::mutex> lock(mutex_);
                                      samples_.push_back(m);
                                    });
    status_ = participant_.make_reader(cover::dds::topics::ugv_status(ugv),
                                       [this](const cover::msg::UgvStatus& m) {
                                         std::lock_guard<std::mutex> lock(mutex_);
                                         last_status_ = m;
                                       });
  }
  std::vector<cover::msg::UgvImu> samples() {
    std::lock_guard<std::mutex> lock(mutex_);
    return samples_;
  }
  std::optional<cover::msg::UgvStatus> status() {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_status_;
  }

 private:
  static cover::dds::ParticipantOptions options(int domain) {
    cover::dds::ParticipantOptions o;
    o.vendor = cover::dds::Vendor::FastDds;
    o.domain_id = domain;
    return o;
  }
  cover::dds::Participant participant_;
  std::mutex mutex_;
  std::vector<cover::msg::UgvImu> samples_;
  std::optional<cover::msg::UgvStatus> last_status_;
  cover::dds::Reader<cover::msg::UgvImu> imu_;
  cover::dds::Reader<cover::msg::UgvStatus> status_;
};

TEST(SimFcProcess, UgvAgentReadsTheImuTheSimulatorServesOverMavlink) {
  auto domain = cover::dds::DomainClaim::claim_any(230, 232);
  const std::uint16_t bind_base = free_port_base(2);
  const std::uint16_t peer_base = free_port_base(2);
  const std::string url = "udpin://127.0.0.1:" + std::to_string(peer_base + 1);
  UgvObserver observer(domain.domain(), 1);
  ChildProcess ugv({bin("cover-ugv-agent"), "--id", "1", "--source", "mavlink", "--url", url},
                   on_domain(domain.domain(), "ugv1.log"));
  ChildProcess sim(
      {bin("cover-sim"), "--clock", "realtime", "--standing", "--run-id", run_id("ugvimu"),
       "--ugv-imu", "mavlink", "--ugv-imu-bind-port-base", std::to_string(bind_base),
       "--ugv-imu-peer-port-base", std::to_string(peer_base)},
      on_domain(domain.domain(), "sim.log"));
  // The world runs once a UAV agent is there (no task: the UAV sits on its deck).
  ChildProcess uav({bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "2"},
                   on_domain(domain.domain(), "uav.log"));

  ASSERT_TRUE(wait_until([&] { return observer.samples().size() >= 400; }, 20s));
  const auto samples = observer.samples();
  std::int64_t previous_ns = -1;
  int distinct = 0;
  int five_ms_apart = 0;
  for (const auto& m : samples) {
    // The agent repeats its last sample (same seq and stamp) when its device is silent for
    // 20 ms, as a loaded machine's realtime simulator can be.
    if (m.stamp_ns == previous_ns) continue;
    EXPECT_GT(m.stamp_ns, previous_ns);    // simulated time, increasing
    EXPECT_EQ(m.stamp_ns % 5'000'000, 0);  // 200 Hz of simulated time, to the nanosecond
    if (m.stamp_ns - previous_ns == 5'000'000) ++five_ms_apart;
    previous_ns = m.stamp_ns;
    ++distinct;
    // A planar UGV: gravity up in FLU, a few m/s^2 at most in the plane, yaw rate only.
    EXPECT_NEAR(m.specific_force_m_s2.z, 9.81, 0.5);
    EXPECT_LT(std::hypot(m.specific_force_m_s2.x, m.specific_force_m_s2.y), 3.0);
    EXPECT_LT(std::abs(m.angular_velocity_rad_s.x), 0.1);
    EXPECT_LT(std::abs(m.angular_velocity_rad_s.y), 0.1);
    EXPECT_LT(std::abs(m.angular_velocity_rad_s.z), 2.0);
  }
  // Best-effort DDS may lose a sample to the test's reader; nearly all follow each other.
  EXPECT_GT(five_ms_apart, distinct * 9 / 10);
  ASSERT_TRUE(wait_until(
      [&] {
        const auto status = observer.status();
        return status && status->samples > 0;
      },
      5s));
  EXPECT_EQ(observer.status()->source, "mavlink:" + url);
  EXPECT_EQ(observer.status()->rejected_samples, 0u);

  EXPECT_EQ(uav.terminate(scaled(10s), SIGINT), 0);
  EXPECT_EQ(sim.terminate(scaled(10s), SIGINT), 0);
  EXPECT_EQ(ugv.terminate(scaled(10s), SIGINT), 0);
}

}  // namespace
