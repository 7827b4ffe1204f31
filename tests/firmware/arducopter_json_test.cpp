// Real ArduCopter (SITL, COVER_ARDUPILOT_SITL) flown on COVER's physics: its JSON backend
// served by firmware_link's ArduPilotJsonLink, driven by a World with the motor-level UAV
// (config/sim/firmware_uav_arducopter.yaml) on a still deck, in lockstep and in realtime.
// The EKF initialises on what the link sends, it arms in GUIDED_NOGPS, and a body-rate +
// thrust stream (SET_ATTITUDE_TARGET on its companion link, sent on the physics clock) lifts
// the plant off and holds a hover; in lockstep the simulator stalls once for 1.5 s, and
// ArduPilot's re-sent packet must not cost a step. Skips without the firmware; fails with
// COVER_REQUIRE_FIRMWARE=1.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/firmware_monitor.hpp"
#include "cover/firmware/instance_slot.hpp"
#include "cover/firmware/params_file.hpp"
#include "cover/firmware/sitl_ports.hpp"
#include "cover/firmware/sitl_process.hpp"
#include "cover/firmware_link/ardupilot_json_link.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/sim/world.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"

namespace cover::firmware::test {
namespace {

using namespace std::chrono_literals;
namespace fl = cover::firmware_link;
namespace mav = cover::mavlink;

constexpr float kGuidedNoGps = 20.0F;
constexpr double kHoverThrust = 0.515;  // arducopter_json.parm's MOT_THST_HOVER
constexpr double kClimbM = 1.5;         // the hover's height above the deck

// The firmware's SERIAL1 (udpclient to 127.0.0.1:14540 + N): the test binds that port and
// answers whatever port the firmware sends from, as cover-fc-bridge's udpin does.
class CompanionLink {
 public:
  explicit CompanionLink(int port) : fd_(::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) != 0) {
      throw std::runtime_error("companion port " + std::to_string(port) + " in use");
    }
  }
  ~CompanionLink() { ::close(fd_); }
  // Reads what the firmware sent (only its address is kept), then sends `setpoint`.
  void send(const mav::SetAttitudeTarget& setpoint) {
    std::uint8_t buffer[2048];
    sockaddr_in from{};
    socklen_t size = sizeof(from);
    while (::recvfrom(fd_, buffer, sizeof(buffer), 0, reinterpret_cast<sockaddr*>(&from), &size) >
           0) {
      peer_ = from;
      size = sizeof(from);
    }
    if (!peer_) return;
    const auto frame = encoder_.encode(setpoint);
    ::sendto(fd_, frame.bytes.data(), frame.size, 0, reinterpret_cast<const sockaddr*>(&*peer_),
             sizeof(*peer_));
  }

 private:
  int fd_;
  std::optional<sockaddr_in> peer_;
  mav::Encoder encoder_{255, 191};
};

struct Sample {
  double t_s;  // firmware time
  double altitude_m;
  double vz_m_s;
  double tilt_rad;
};

// The physics thread: settle_uav (the decks held still) + exchange, and every 10 ms of
// firmware time the setpoint, computed from the plant's state (an altitude hold around the
// firmware's attitude hold) and sent before the next answer, so that the firmware reads it
// at a fixed point of its own clock.
class PhysicsLoop {
 public:
  PhysicsLoop(fl::ArduPilotJsonLink& link, CompanionLink& companion, std::uint8_t system_id)
      : world_(sim::WorldParams::load_file(COVER_CONFIG_DIR "/sim/world_default.yaml"),
               sim::FirmwareUavParams::load_file(
                   COVER_CONFIG_DIR "/sim/firmware_uav_arducopter.yaml",
                   sim::WorldParams::load_file(COVER_CONFIG_DIR "/sim/world_default.yaml")
                       .physics_rate_hz)),
        link_(link),
        companion_(companion),
        system_id_(system_id),
        start_altitude_m_(world_.state().uav.position_m.z) {
    thread_ = std::thread([this] { run(); });
  }
  ~PhysicsLoop() { stop(); }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

  bool connected() const { return connected_; }
  double firmware_time_s() const { return firmware_time_s_; }
  double start_altitude_m() const { return start_altitude_m_; }
  void hover() { hover_ = true; }
  // The simulator stalls once for `stall` before answering the frame after firmware time
  // `at_s` (a fault injected: ArduPilot re-sends its packet after ~1 s without an answer).
  void stall_at(double at_s, std::chrono::milliseconds stall) {
    stall_ = stall;
    stall_at_s_ = at_s;
  }
  std::vector<Sample> trace() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return trace_;
  }
  double wall_s() const { return wall_s_; }

 private:
  void run() {
    const auto start = std::chrono::steady_clock::now();
    while (!stop_ && !link_.wait_for_firmware(100ms)) {
    }
    connected_ = link_.connected();
    sim::MotorOutputs outputs{};
    std::uint64_t step = 0;
    while (!stop_ && connected_) {
      world_.settle_uav(outputs);
      const auto& uav = world_.state().uav;
      firmware_time_s_ = world_.motor_uav().firmware_time_s();
      if (++step % 10 == 0) {
        companion_.send(setpoint(uav));
        record(uav);
      }
      if (stall_at_s_ >= 0.0 && firmware_time_s_ >= stall_at_s_) {
        stall_at_s_ = -1.0;
        std::this_thread::sleep_for(stall_);  // the fault under test, not a synchronisation
      }
      outputs = link_.exchange(fl::plant_sample(world_.motor_uav(), uav));
    }
    wall_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  mav::SetAttitudeTarget setpoint(const sim::QuadrotorState& uav) const {
    mav::SetAttitudeTarget s;
    s.time_boot_ms = static_cast<std::uint32_t>(firmware_time_s_ * 1000.0);
    s.target_system = system_id_;
    s.target_component = 1;
    s.type_mask = 128;  // rates and thrust, no attitude: rates 0 hold the attitude
    s.thrust = 0.0F;
    if (hover_) {
      // A PD altitude hold on the plant's truth, as COVER's agent would fly it.
      const double error = start_altitude_m_ + kClimbM - uav.position_m.z;
      const double a = 2.0 * error - 2.5 * uav.velocity_m_s.z;
      s.thrust = static_cast<float>(std::clamp(kHoverThrust * (1.0 + a / 9.81), 0.2, 0.8));
    }
    return s;
  }

  void record(const sim::QuadrotorState& uav) {
    const Eigen::Vector3d up = uav.attitude.eigen() * Eigen::Vector3d::UnitZ();
    std::lock_guard<std::mutex> lock(mutex_);
    trace_.push_back({firmware_time_s_, uav.position_m.z - start_altitude_m_, uav.velocity_m_s.z,
                      std::acos(std::clamp(up.z(), -1.0, 1.0))});
  }

  sim::World world_;
  fl::ArduPilotJsonLink& link_;
  CompanionLink& companion_;
  std::uint8_t system_id_;
  double start_altitude_m_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> connected_{false};
  std::atomic<bool> hover_{false};
  std::atomic<double> stall_at_s_{-1.0};
  std::chrono::milliseconds stall_{0};
  std::atomic<double> firmware_time_s_{0.0};
  std::atomic<double> wall_s_{0.0};
  mutable std::mutex mutex_;
  std::vector<Sample> trace_;
  std::thread thread_;
};

// Ready = the firmware accepts the arm command in GUIDED_NOGPS (its pre-arm checks, the EKF
// among them): the firmware time it armed at, or nullopt when it never did.
std::optional<double> arm_in_guided_nogps(FirmwareMonitor& monitor, const PhysicsLoop& physics) {
  const auto deadline = std::chrono::steady_clock::now() + cover::test::scaled(120s);
  while (std::chrono::steady_clock::now() < deadline) {
    const double t = physics.firmware_time_s();
    // The mode each time: a mode set while the firmware initialises is replaced by its
    // initial mode once it is ready.
    const auto mode = monitor.set_mode(kGuidedNoGps);
    const auto arm = monitor.command(mav::mav_cmd::kComponentArmDisarm, {1, 0, 0, 0, 0, 0, 0},
                                     cover::test::scaled(5s));
    if (mode == mav::mav_result::kAccepted && arm == mav::mav_result::kAccepted) {
      return physics.firmware_time_s();
    }
    // Refused: asked again one firmware second later (a condition on its clock).
    cover::test::wait_until([&] { return physics.firmware_time_s() >= t + 1.0; }, 10s, 1ms);
  }
  return std::nullopt;
}

struct HoverQuality {
  double climb_m = 0.0;  // the highest point after arming, above the deck
  // Over the last 10 s of the 25 s after arming (firmware time):
  double altitude_error_max_m = 0.0;
  double altitude_error_rms_m = 0.0;
  double vz_max_m_s = 0.0;
  double tilt_max_rad = 0.0;
  int samples = 0;
};

HoverQuality hover_quality(const std::vector<Sample>& trace, double t_arm) {
  HoverQuality q;
  double error_sq = 0.0;
  for (const auto& s : trace) {
    if (s.t_s < t_arm) continue;
    q.climb_m = std::max(q.climb_m, s.altitude_m);
    if (s.t_s < t_arm + 15.0) continue;
    const double e = s.altitude_m - kClimbM;
    q.altitude_error_max_m = std::max(q.altitude_error_max_m, std::abs(e));
    error_sq += e * e;
    q.vz_max_m_s = std::max(q.vz_max_m_s, std::abs(s.vz_m_s));
    q.tilt_max_rad = std::max(q.tilt_max_rad, s.tilt_rad);
    ++q.samples;
  }
  if (q.samples > 0) q.altitude_error_rms_m = std::sqrt(error_sq / q.samples);
  return q;
}

// One line per firmware second from 1 s before arming: the climb and the hover.
void print_trace(const std::vector<Sample>& trace, double t_arm) {
  for (const auto& s : trace) {
    if (s.t_s >= t_arm - 1.0 && std::fmod(s.t_s, 1.0) < 0.005) {
      std::printf("  t %6.2f s  altitude %6.3f m  vz %6.3f m/s  tilt %5.2f deg\n", s.t_s - t_arm,
                  s.altitude_m, s.vz_m_s, s.tilt_rad * 180.0 / M_PI);
    }
  }
}

class ArduCopterJson : public ::testing::Test {
 protected:
  void SetUp() override {
    lookup_ = find_arducopter_sitl();
    if (lookup_.build) return;
    if (firmware_required()) FAIL() << lookup_.missing << " (COVER_REQUIRE_FIRMWARE=1)";
    GTEST_SKIP() << lookup_.missing;
  }
  FirmwareLookup lookup_;
};

// Boots the firmware on the physics, arms it in GUIDED_NOGPS, hovers 25 s (firmware time)
// and checks the exchange and the hover. Realtime: the firmware paces itself to the wall
// clock (no "no_time_sync"), and the physics steps as its packets come, stepping on without
// one after the link's realtime timeout.
void boot_arm_and_hover(const FirmwareBuild& build, fl::Pacing pacing) {
  InstanceSlot slot = InstanceSlot::claim(Autopilot::ArduPilot, 4, 9);
  const int n = slot.instance();
  fl::ArduPilotJsonLinkOptions options;
  options.port = cover::firmware::physics_port(cover::Autopilot::ArduPilot, n);
  options.pacing = pacing;
  fl::ArduPilotJsonLink link(options);
  CompanionLink companion(companion_port(n));
  const auto params = read_params_file(COVER_CONFIG_DIR "/firmware/arducopter_json.parm");
  const auto workdir = cover::test::scratch_dir() / "arducopter_json";
  const auto boot = std::chrono::steady_clock::now();
  SitlProcess sitl = SitlProcess::start_arducopter_json(build, std::move(slot), workdir, params);
  std::printf("ArduCopter JSON instance %d in %s, physics on UDP %d\n", n, workdir.c_str(),
              link.port());
  PhysicsLoop physics(link, companion, static_cast<std::uint8_t>(sitl.system_id()));
  auto monitor = FirmwareMonitor::arducopter(n);
  auto report_texts = [&] {
    for (const auto& t : monitor->texts()) std::printf("  firmware: %s\n", t.value.c_str());
  };

  ASSERT_TRUE(cover::test::wait_until([&] { return physics.connected(); }, 30s))
      << "no servo packet from the firmware on UDP " << link.port();
  ASSERT_TRUE(cover::test::wait_until([&] { return monitor->connected(); }, 30s));

  const auto ready_fw_s = arm_in_guided_nogps(*monitor, physics);
  const bool armed = ready_fw_s.has_value();
  const double ready_wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - boot).count();
  if (!armed) report_texts();
  ASSERT_TRUE(armed) << "the firmware never accepted arming in GUIDED_NOGPS";
  const double t_arm = physics.firmware_time_s();
  const bool lockstep = pacing == fl::Pacing::Lockstep;
  if (lockstep) physics.stall_at(t_arm + 10.0, 1500ms);
  physics.hover();
  ASSERT_TRUE(cover::test::wait_until([&] { return physics.firmware_time_s() >= t_arm + 25.0; },
                                      180s, 10ms));
  const auto heartbeat = monitor->heartbeat();
  physics.stop();
  sitl.stop();
  report_texts();

  const auto trace = physics.trace();
  print_trace(trace, t_arm);
  const HoverQuality hover = hover_quality(trace, t_arm);
  ASSERT_GT(hover.samples, 0);
  const double fw_s = physics.firmware_time_s();
  const auto stats = link.stats();
  const auto ap = link.ardupilot_stats();
  std::printf(
      "boot to ready: %.1f s wall, %.1f s firmware; %.1f s firmware in %.1f s wall: "
      "%.0f frames/s, real-time factor %.2f\n"
      "frames answered %llu, servo packets %llu, missed %llu, repeats answered %llu / dropped "
      "%llu, restarts %llu, skipped %llu, rejected %llu, frame rate %u Hz\n"
      "hover (last 10 s): altitude error max %.3f m rms %.3f m, |vz| max %.3f m/s, tilt max "
      "%.2f deg; climbed to %.2f m\n",
      ready_wall_s, *ready_fw_s, fw_s, physics.wall_s(), stats.frames_sent / physics.wall_s(),
      fw_s / physics.wall_s(), static_cast<unsigned long long>(stats.frames_sent),
      static_cast<unsigned long long>(stats.answers),
      static_cast<unsigned long long>(stats.answers_missed),
      static_cast<unsigned long long>(ap.repeats_answered),
      static_cast<unsigned long long>(ap.repeats_dropped),
      static_cast<unsigned long long>(ap.restarts),
      static_cast<unsigned long long>(ap.frames_skipped),
      static_cast<unsigned long long>(stats.frames_rejected), ap.frame_rate_hz,
      hover.altitude_error_max_m, hover.altitude_error_rms_m, hover.vz_max_m_s,
      hover.tilt_max_rad * 180.0 / M_PI, hover.climb_m);

  ASSERT_TRUE(heartbeat);
  EXPECT_TRUE(armed && (heartbeat->base_mode & mav::mav_mode_flag::kSafetyArmed) != 0)
      << "disarmed during the hover";
  EXPECT_EQ(heartbeat->custom_mode, static_cast<std::uint32_t>(kGuidedNoGps));
  // One answer per servo packet, ArduPilot's frame_count +1 per answer. Lockstep: no step
  // without its packet. Realtime: the firmware keeps the wall clock, and a step without its
  // packet is rare.
  const double realtime_factor = fw_s / physics.wall_s();
  if (lockstep) {
    EXPECT_EQ(stats.answers_missed, 0u);
    EXPECT_GT(realtime_factor, 1.0);
  } else {
    EXPECT_LT(stats.answers_missed, stats.frames_sent / 100) << "more than 1 % of the steps";
    EXPECT_GT(realtime_factor, 0.8);
    EXPECT_LT(realtime_factor, 1.1);
  }
  EXPECT_EQ(ap.restarts, 0u);
  EXPECT_EQ(ap.frames_skipped, 0u);
  EXPECT_EQ(stats.frames_rejected, 0u);
  EXPECT_EQ(ap.frame_rate_hz, 1000);
  EXPECT_LE(stats.answers - stats.frames_sent, 1u);
  // A fresh firmware counts from frame 0: its last frame_count is the number of answers.
  EXPECT_EQ(ap.last_frame_count, stats.frames_sent);
  EXPECT_EQ(ap.repeats_answered, 0u);
  if (lockstep) {
    // The stall: ArduPilot re-sent the frame it waited for; the answer overtook the repeat.
    EXPECT_GE(ap.repeats_dropped, 1u);
  }
  // It lifted off and holds the hover.
  EXPECT_GT(hover.climb_m, 1.0);
  // The thrust that hovers is the firmware's MOT_THST_HOVER (no battery compensation): the
  // altitude hold's P term needs next to no offset (0.112 m with copter.parm's compensation).
  EXPECT_LT(hover.altitude_error_max_m, 0.05);
  EXPECT_LT(hover.vz_max_m_s, 0.3);
  EXPECT_LT(hover.tilt_max_rad, 2.0 * M_PI / 180.0);
}

TEST_F(ArduCopterJson, BootsArmsAndHoversOnCoverPhysicsInLockstep) {
  boot_arm_and_hover(*lookup_.build, fl::Pacing::Lockstep);
}

TEST_F(ArduCopterJson, BootsArmsAndHoversOnCoverPhysicsInRealtime) {
  boot_arm_and_hover(*lookup_.build, fl::Pacing::Realtime);
}

}  // namespace
}  // namespace cover::firmware::test
