// cover-sim's MAVLink side as real processes on free UDP ports: a test-side MAVLink client
// (our codec on a UDP socket) meets the simulated autopilot, and cover-ugv-agent reads the
// UGV IMU that cover-sim serves as a rover autopilot and publishes it on DDS.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
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
  // Reads what is there: a socket left unread overflows and drops what comes next. Counts
  // each message id, and keeps HIGHRES_IMU's stamps.
  void drain(std::chrono::milliseconds first_wait = 0ms) {
    std::array<std::uint8_t, 2048> buffer{};
    auto wait = first_wait;
    while (const std::size_t n = link_->read(buffer.data(), buffer.size(), wait)) {
      wait = 0ms;
      parser_.feed(buffer.data(), n, [&](const mav::Frame& frame) {
        ++counts_[frame.message_id];
        if (const auto imu = mav::decode<mav::HighresImu>(frame))
          imu_stamps_us_.push_back(imu->time_usec);
        if (const auto text = mav::decode<mav::StatusText>(frame))
          texts_.push_back(text->text_string());
      });
    }
  }
  void forget() {
    counts_.clear();
    imu_stamps_us_.clear();
    texts_.clear();
  }
  std::map<std::uint32_t, int> counts() const { return counts_; }
  const std::vector<std::uint64_t>& imu_stamps_us() const { return imu_stamps_us_; }
  const std::vector<std::string>& texts() const { return texts_; }
  std::uint8_t last_system() const { return last_system_; }
  const mav::ParserStats& stats() const { return parser_.stats(); }

 private:
  std::unique_ptr<mav::Link> link_;
  mav::StreamParser parser_;
  mav::Encoder encoder_{245, mav::mav_comp::kOnboardComputer};
  std::uint8_t last_system_ = 0;
  std::map<std::uint32_t, int> counts_;
  std::vector<std::uint64_t> imu_stamps_us_;
  std::vector<std::string> texts_;
};

struct Profile {
  const char* name;
  std::uint8_t autopilot;
  std::uint32_t start_mode;
  std::uint32_t offboard_main;
  int offboard_acks;        // PX4 answers DO_SET_MODE twice
  std::uint8_t arm_result;  // armed in the offboard mode with no setpoint stream
};

mav::CommandLong command_to(std::uint8_t system, std::uint16_t id, float p1 = 0.0F,
                            float p2 = 0.0F) {
  mav::CommandLong c;
  c.command = id;
  c.param[0] = p1;
  c.param[1] = p2;
  c.target_system = system;
  c.target_component = 1;
  return c;
}

// Over UDP, as PX4 SITL and ArduCopter SITL did: the boot mode in the HEARTBEAT, the
// offboard mode granted with no setpoint stream (PX4 twice), and the arm then refused by
// PX4 (1) and granted by ArduPilot (0).
void heartbeats_offboard_and_arm(const Profile& profile) {
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

  auto offboard = command_to(client.last_system(), mav::mav_cmd::kDoSetMode,
                             mav::mav_mode_flag::kCustomModeEnabled);
  offboard.param[1] = static_cast<float>(profile.offboard_main);
  client.send(offboard);
  for (int i = 0; i < profile.offboard_acks; ++i) {
    const auto ack = client.wait_for<mav::CommandAck>(scaled(3s));
    ASSERT_TRUE(ack) << "ACK " << i;
    EXPECT_EQ(ack->command, mav::mav_cmd::kDoSetMode);
    EXPECT_EQ(ack->result, mav::mav_result::kAccepted);
    EXPECT_EQ(ack->target_system, 245);
  }
  client.send(command_to(client.last_system(), mav::mav_cmd::kComponentArmDisarm, 1.0F));
  const auto arm = client.wait_for<mav::CommandAck>(scaled(3s));
  ASSERT_TRUE(arm);
  EXPECT_EQ(arm->command, mav::mav_cmd::kComponentArmDisarm);  // not a third mode ACK
  EXPECT_EQ(arm->result, profile.arm_result);
  EXPECT_EQ(client.stats().errors(), 0u);

  EXPECT_EQ(sim.terminate(scaled(10s), SIGINT), 0);  // a standing world ends by being stopped
}

TEST(SimFcProcess, Px4AcceptsOffboardWithoutASetpointStreamAndRefusesTheArm) {
  heartbeats_offboard_and_arm(
      {"px4", mav::mav_autopilot::kPx4,
       mav::px4_mode::custom_mode(mav::px4_mode::kMainAuto, mav::px4_mode::kAutoSubLoiter),
       mav::px4_mode::kMainOffboard, 2, mav::mav_result::kTemporarilyRejected});
}

TEST(SimFcProcess, ArduPilotAcceptsGuidedNoGpsWithoutASetpointStreamAndArmsInIt) {
  heartbeats_offboard_and_arm({"ardupilot", mav::mav_autopilot::kArdupilotMega,
                               mav::copter_mode::kStabilize, mav::copter_mode::kGuidedNoGps, 1,
                               mav::mav_result::kAccepted});
}

// The newest tick of cover/sim/clock, s (< 0: none yet).
class SimClockWatch {
 public:
  explicit SimClockWatch(int domain) : participant_(options(domain)) {
    reader_ = participant_.make_reader(cover::dds::topics::sim_clock(),
                                       [this](const cover::msg::SimClock& tick) {
                                         std::lock_guard<std::mutex> lock(mutex_);
                                         t_s_ = std::max(t_s_, tick.stamp_ns * 1e-9);
                                       });
  }
  double t_s() {
    std::lock_guard<std::mutex> lock(mutex_);
    return t_s_;
  }
  cover::dds::Participant& participant() { return participant_; }

 private:
  static cover::dds::ParticipantOptions options(int domain) {
    cover::dds::ParticipantOptions o;
    o.vendor = cover::dds::Vendor::FastDds;
    o.domain_id = domain;
    return o;
  }
  cover::dds::Participant participant_;
  std::mutex mutex_;
  double t_s_ = -1.0;
  cover::dds::Reader<cover::msg::SimClock> reader_;
};

// ArduCopter SITL over UDP: nothing but HEARTBEAT until asked, no STATUSTEXT to a link that
// has never sent a frame (its EKF aligns meanwhile, unheard); HIGHRES_IMU at the asked
// 100 Hz (each simulated 10 ms, read from its stamps); "Arming motors" once it has heard us.
TEST(SimFcProcess, ArduPilotSendsOnlyHeartbeatsAndTextsNoLinkUntilAskedOverUdp) {
  auto domain = cover::dds::DomainClaim::claim_any(230, 232);
  const std::uint16_t bind_base = free_port_base(1);
  const std::uint16_t peer_base = free_port_base(1);
  MavlinkClient client(peer_base);
  SimClockWatch clock(domain.domain());
  ChildProcess sim({bin("cover-sim"), "--fc", "ardupilot", "--clock", "realtime", "--standing",
                    "--run-id", run_id("apstreams"), "--fc-bind-port-base",
                    std::to_string(bind_base), "--fc-peer-port-base", std::to_string(peer_base)},
                   on_domain(domain.domain(), "sim.log"));
  // The world runs once a UAV agent is there (no task: the UAV sits on its deck).
  ChildProcess uav({bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "2"},
                   on_domain(domain.domain(), "uav.log"));
  // Past EKF3's alignment at 1 s of simulated time.
  ASSERT_TRUE(wait_until(
      [&] {
        client.drain(20ms);
        return clock.t_s() >= 2.0;
      },
      scaled(30s)))
      << "the world never ran";
  const auto counts = client.counts();
  EXPECT_GE(counts.at(mav::Heartbeat::kId), 2);
  EXPECT_EQ(counts.size(), 1u) << "a message other than HEARTBEAT before any request";
  EXPECT_TRUE(client.texts().empty());

  client.send(command_to(1, mav::mav_cmd::kSetMessageInterval,
                         static_cast<float>(mav::HighresImu::kId), 10000.0F));
  const auto ack = client.wait_for<mav::CommandAck>(scaled(3s));
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->result, mav::mav_result::kAccepted);
  client.forget();
  const auto& stamps = client.imu_stamps_us();
  ASSERT_TRUE(wait_until(
      [&] {
        client.drain(20ms);
        return stamps.size() >= 100;
      },
      scaled(10s)));
  int ten_ms_apart = 0;
  for (std::size_t i = 1; i < stamps.size(); ++i)
    ten_ms_apart += stamps[i] - stamps[i - 1] == 10000;
  EXPECT_GE(ten_ms_apart, static_cast<int>(stamps.size()) * 9 / 10);  // every simulated step

  client.send(command_to(1, mav::mav_cmd::kDoSetMode, 1.0F,
                         static_cast<float>(mav::copter_mode::kGuidedNoGps)));
  client.send(command_to(1, mav::mav_cmd::kComponentArmDisarm, 1.0F));
  ASSERT_TRUE(wait_until(
      [&] {
        client.drain(20ms);
        const auto& texts = client.texts();
        return std::find(texts.begin(), texts.end(), "Arming motors") != texts.end();
      },
      scaled(5s)));
  EXPECT_EQ(uav.terminate(scaled(10s), SIGINT), 0);
  EXPECT_EQ(sim.terminate(scaled(10s), SIGINT), 0);
}

// cover/uav/0/fc as the test sees it: the newest state.
class FcStateWatch {
 public:
  FcStateWatch(cover::dds::Participant& participant) {
    reader_ = participant.make_reader(cover::dds::topics::fc_state(0),
                                      [this](const cover::msg::FcState& s) {
                                        std::lock_guard<std::mutex> lock(mutex_);
                                        last_ = s;
                                      });
  }
  std::optional<cover::msg::FcState> last() {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_;
  }

 private:
  std::mutex mutex_;
  std::optional<cover::msg::FcState> last_;
  cover::dds::Reader<cover::msg::FcState> reader_;
};

// The real cover-fc-bridge on cover-sim's autopilot: it asks its streams and they all
// arrive, reads every parameter (as the simulated firmware types them), sees the estimator
// aligned; PX4's unknown message types are skipped, not errors. A wrong ATC_ANGLE_BOOST set in
// the simulator's sim_fc.yaml becomes the bridge's flight_blocker.
void real_bridge_on_the_simulated_autopilot(const std::string& autopilot, bool wrong_boost) {
  auto domain = cover::dds::DomainClaim::claim_any(230, 232);
  const std::uint16_t bind_base = free_port_base(1);
  const std::uint16_t peer_base = free_port_base(1);
  std::vector<std::string> sim_args = {bin("cover-sim"),
                                       "--fc",
                                       autopilot,
                                       "--clock",
                                       "realtime",
                                       "--standing",
                                       "--run-id",
                                       run_id("bridge" + autopilot),
                                       "--fc-bind-port-base",
                                       std::to_string(bind_base),
                                       "--fc-peer-port-base",
                                       std::to_string(peer_base)};
  if (wrong_boost) {
    const std::string params = cover::test::scratch_path("sim_fc.yaml");
    std::ofstream(params) << "sim_fc:\n  ardupilot:\n    atc_angle_boost: 1\n";
    sim_args.insert(sim_args.end(), {"--fc-params", params});
  }
  SimClockWatch clock(domain.domain());
  FcStateWatch fc(clock.participant());
  ChildProcess sim(sim_args, on_domain(domain.domain(), "sim.log"));
  ChildProcess bridge({bin("cover-fc-bridge"), "--id", "0", "--autopilot", autopilot, "--url",
                       "udpin://127.0.0.1:" + std::to_string(peer_base), "--clock", "realtime"},
                      on_domain(domain.domain(), "bridge.log"));
  ChildProcess uav({bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "2",
                    "--fc-bridge"},
                   on_domain(domain.domain(), "uav.log"));
  // Every stream asked and arriving, every parameter read: a few seconds of the world.
  ASSERT_TRUE(wait_until([&] { return clock.t_s() >= 4.0; }, scaled(60s))) << "the world never ran";
  std::optional<cover::msg::FcState> s;
  ASSERT_TRUE(wait_until(
      [&] {
        s = fc.last();
        return s && s->streams_missing.empty() && !s->streams.empty() && s->estimator_ok &&
               !s->parameters.empty() && (!wrong_boost || !s->flight_blocker.empty());
      },
      scaled(20s)))
      << (s ? "streams_missing '" + s->streams_missing + "', estimator '" + s->estimator +
                  "', flight_blocker '" + s->flight_blocker + "'"
            : std::string("no cover/uav/0/fc"));
  EXPECT_TRUE(s->link_ok);
  for (const auto& stream : s->streams) EXPECT_TRUE(stream.arriving) << stream.name;
  for (const auto& p : s->parameters) {
    if (p.name == "SYSID_THISMAV") continue;  // MAV_SYSID's old name
    EXPECT_TRUE(p.known) << p.name;
  }
  EXPECT_EQ(s->rx_errors, 0u);
  if (autopilot == "px4") {
    EXPECT_GT(s->rx_unknown, 0u);
  }
  if (wrong_boost) {
    EXPECT_NE(s->flight_blocker.find("ATC_ANGLE_BOOST is 1"), std::string::npos)
        << s->flight_blocker;
  } else {
    EXPECT_EQ(s->flight_blocker, "");
  }
  EXPECT_EQ(uav.terminate(scaled(10s), SIGINT), 0);
  EXPECT_EQ(bridge.terminate(scaled(10s), SIGINT), 0);
  EXPECT_EQ(sim.terminate(scaled(10s), SIGINT), 0);
}

TEST(SimFcProcess, RealBridgeOnThePx4ReadsItsStreamsParametersAndEstimator) {
  real_bridge_on_the_simulated_autopilot("px4", false);
}

TEST(SimFcProcess, RealBridgeHoldsFlightsOnTheArduPilotsWrongAngleBoost) {
  real_bridge_on_the_simulated_autopilot("ardupilot", true);
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
  // The simulator's lockstep contract: every step closed by a HIGHRES_IMU stamped with it,
  // though PX4's stream is 50 Hz and nobody asked for more.
  companion.mavlink().drain(100ms);
  const auto& stamps = companion.mavlink().imu_stamps_us();
  ASSERT_GE(stamps.size(), 149u);
  for (std::size_t i = 0; i < 149; ++i) EXPECT_EQ(stamps[i], i * 10000) << i;
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
