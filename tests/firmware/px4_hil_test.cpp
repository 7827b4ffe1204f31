// Real PX4 SITL flies COVER's motor-level plant through simulator_mavlink (HIL over TCP,
// sim/firmware_link/px4_hil_link.hpp): PX4 (airframe 10016, config/firmware/px4_hil.params)
// boots on Px4HilLink's sensor frames with the UAV resting on the ground of a World
// (config/sim/firmware_uav_px4.yaml), its estimator aligns, it arms and enters OFFBOARD,
// and a body-rate + thrust stream on its companion link (UDP 14540 + N, as cover-fc-bridge
// speaks it) lifts the plant off and holds a hover. Found through COVER_PX4_SITL; skips
// without, fails with COVER_REQUIRE_FIRMWARE=1.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/firmware_monitor.hpp"
#include "cover/firmware/instance_slot.hpp"
#include "cover/firmware/params_file.hpp"
#include "cover/firmware/sitl_ports.hpp"
#include "cover/firmware/sitl_process.hpp"
#include "cover/firmware_link/px4_hil_link.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/sim/world.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"

namespace cover::firmware::test {
namespace {

namespace mav = cover::mavlink;
using cover::firmware_link::Pacing;
using cover::firmware_link::Px4HilConfig;
using cover::firmware_link::Px4HilLink;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr double kHoverAltitudeM = 1.5;
constexpr double kHoverOutput = 0.515;  // the plant's: 1.05 kg * 9.81 / 20 N

std::string config_path(const std::string& relative) {
  return config::default_config_dir() + "/" + relative;
}

// The plant's truth, copied out of the physics thread.
struct Truth {
  sim::QuadrotorState body;
  double firmware_time_s = 0.0;
  std::array<double, 4> outputs{};
};

// The World stepped by the link, in a thread of its own: each physics step, then the
// exchange with PX4 (which waits for PX4's answer in lockstep).
class PhysicsLoop {
 public:
  PhysicsLoop(sim::World& world, Px4HilLink& link) : world_(world), link_(link) {
    thread_ = std::thread([this] { run(); });
  }
  ~PhysicsLoop() { stop(); }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  Truth truth() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return truth_;
  }
  void release_deck() { settling_ = false; }
  // From now on the firmware's clock runs at most as fast as the wall clock: the companion's
  // stream and the test's sampling run on wall time. Before it, as fast as PX4 answers.
  void pace_to_wall_clock() { pace_ = true; }

 private:
  void run() {
    sim::MotorOutputs outputs{};
    bool paced = false;
    std::chrono::steady_clock::time_point wall_anchor;
    double firmware_anchor_s = 0.0;
    while (!stop_) {
      const double now_s = world_.motor_uav().firmware_time_s();
      if (pace_ && !paced) {
        paced = true;
        wall_anchor = std::chrono::steady_clock::now();
        firmware_anchor_s = now_s;
      }
      if (paced) {
        // Pacing the simulation to real time, not synchronising with anything.
        std::this_thread::sleep_until(
            wall_anchor + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(now_s - firmware_anchor_s)));
      }
      if (settling_) {
        world_.settle_uav(outputs);
      } else {
        world_.step(outputs);
      }
      outputs = link_.exchange(firmware_link::plant_sample(world_.motor_uav(), world_.state().uav));
      std::lock_guard<std::mutex> lock(mutex_);
      truth_.body = world_.state().uav;
      truth_.firmware_time_s = world_.motor_uav().firmware_time_s();
      truth_.outputs = outputs;
    }
  }

  sim::World& world_;
  Px4HilLink& link_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> settling_{true};
  std::atomic<bool> pace_{false};
  mutable std::mutex mutex_;
  Truth truth_;
  std::thread thread_;
};

// A companion's SET_ATTITUDE_TARGET stream (body rates FRD + thrust, type_mask 128), as
// cover-fc-bridge sends it, on PX4's onboard link, from a small hover controller on the
// plant's truth: level the vehicle against its horizontal velocity, hold the altitude.
class HoverStream {
 public:
  HoverStream(int instance, const PhysicsLoop& physics)
      : physics_(physics),
        link_(mav::make_udp_link("127.0.0.1", static_cast<std::uint16_t>(companion_port(instance)),
                                 "127.0.0.1",
                                 static_cast<std::uint16_t>(px4_onboard_port(instance)))),
        encoder_(static_cast<std::uint8_t>(instance + 1), mav::mav_comp::kOnboardComputer),
        target_system_(static_cast<std::uint8_t>(instance + 1)) {
    opened_ = link_->open();
    thread_ = std::thread([this] { run(); });
  }
  ~HoverStream() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  bool opened() const { return opened_; }
  void fly(bool on) { flying_ = on; }
  std::uint64_t sent() const { return sent_; }

 private:
  void run() {
    std::array<std::uint8_t, 512> drain{};
    while (!stop_) {
      send(physics_.truth());
      // PX4's onboard stream to us: read and dropped (the monitor watches the firmware).
      link_->read(drain.data(), drain.size(), milliseconds(20));  // paces the stream: 50 Hz
    }
  }

  void send(const Truth& truth) {
    mav::SetAttitudeTarget m;
    m.time_boot_ms = static_cast<std::uint32_t>(truth.firmware_time_s * 1000.0);
    m.target_system = target_system_;
    m.target_component = mav::mav_comp::kAutopilot1;
    m.type_mask = mav::attitude_target_typemask::kIgnoreAttitude;
    m.thrust = 0.0F;
    if (flying_) command(truth, m);
    const mav::EncodedFrame frame = encoder_.encode(m);
    if (link_->write(frame.bytes.data(), frame.size)) ++sent_;
  }

  // Small gains on the truth: a companion, not a controller under test.
  static void command(const Truth& truth, mav::SetAttitudeTarget& m) {
    const Eigen::Quaterniond q = truth.body.attitude.eigen().normalized();
    const Eigen::Matrix3d r = q.toRotationMatrix();
    const double yaw = std::atan2(r(1, 0), r(0, 0));
    const Eigen::Vector3d v = truth.body.velocity_m_s.eigen();
    // Horizontal velocity in the heading frame; the tilt that brakes it (FLU: +pitch
    // accelerates forward, +roll accelerates left... to the right is -y: roll = -a_y / g).
    const double vx = std::cos(yaw) * v.x() + std::sin(yaw) * v.y();
    const double vy = -std::sin(yaw) * v.x() + std::cos(yaw) * v.y();
    const double pitch_wanted = std::clamp(-0.3 * vx, -0.2, 0.2);
    const double roll_wanted = std::clamp(0.3 * vy, -0.2, 0.2);
    const Eigen::Vector3d up = r.col(2);  // body z in the world
    // Small-angle roll and pitch of the body (FLU): up tilted toward +x is a positive pitch.
    const Eigen::Vector3d up_heading(std::cos(yaw) * up.x() + std::sin(yaw) * up.y(),
                                     -std::sin(yaw) * up.x() + std::cos(yaw) * up.y(), up.z());
    const double pitch = std::asin(std::clamp(up_heading.x(), -1.0, 1.0));
    const double roll = -std::asin(std::clamp(up_heading.y(), -1.0, 1.0));
    const double roll_rate_flu = 4.0 * (roll_wanted - roll);
    const double pitch_rate_flu = 4.0 * (pitch_wanted - pitch);
    m.body_roll_rate = static_cast<float>(roll_rate_flu);     // FRD x = FLU x
    m.body_pitch_rate = static_cast<float>(-pitch_rate_flu);  // FRD y = -FLU y
    m.body_yaw_rate = 0.0F;
    const double z = truth.body.position_m.z;
    const double climb = std::clamp(1.2 * (kHoverAltitudeM - z), -0.8, 0.8);  // m/s wanted
    const double thrust = kHoverOutput * (1.0 + 0.5 * (climb - v.z())) / std::max(0.7, up.z());
    m.thrust = static_cast<float>(std::clamp(thrust, 0.1, 0.85));
  }

  const PhysicsLoop& physics_;
  std::unique_ptr<mav::Link> link_;
  mav::Encoder encoder_;
  std::uint8_t target_system_;
  bool opened_ = false;
  std::atomic<bool> flying_{false};
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> sent_{0};
  std::thread thread_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class Px4Hil : public ::testing::Test {
 protected:
  void SetUp() override {
    lookup_ = find_px4_sitl();
    if (lookup_.build) return;
    if (firmware_required()) FAIL() << lookup_.missing << " (COVER_REQUIRE_FIRMWARE=1)";
    GTEST_SKIP() << lookup_.missing;
  }
  const FirmwareBuild& build() const { return *lookup_.build; }
  FirmwareLookup lookup_;
};

// Lockstep: the loop runs as fast as PX4 answers until PX4 has aligned, then paced to the
// wall clock for the companion's stream. Realtime: paced from the start, each frame waits
// only a few ms for its answer.
void boot_align_arm_and_hover(const FirmwareBuild& build, Pacing pacing) {
  InstanceSlot slot = InstanceSlot::claim(Autopilot::Px4, 4, 9);
  const int n = slot.instance();
  Px4HilConfig config;
  config.port = static_cast<std::uint16_t>(cover::firmware::physics_port(cover::Autopilot::Px4, n));
  config.pacing = pacing;
  const bool lockstep = pacing == Pacing::Lockstep;
  Px4HilLink link(config);  // listening before PX4 starts: it connects at once
  ASSERT_EQ(link.port(),
            static_cast<std::uint16_t>(cover::firmware::physics_port(cover::Autopilot::Px4, n)));

  sim::WorldParams world_params =
      sim::WorldParams::load_file(config_path("sim/world_default.yaml"));
  world_params.uav_initial.start_on_ugv = -1;  // on the ground, away from the UGVs
  world_params.uav_initial.position_m = Eigen::Vector3d(-5.0, -5.0, 0.0);
  sim::World world(world_params,
                   sim::FirmwareUavParams::load_file(config_path("sim/firmware_uav_px4.yaml"),
                                                     world_params.physics_rate_hz));

  const auto started = std::chrono::steady_clock::now();
  SitlProcess px4 =
      SitlProcess::start_px4_hil(build, std::move(slot), cover::test::scratch_path("px4_hil"),
                                 read_params_file(config_path("firmware/px4_hil.params")));
  ASSERT_TRUE(link.wait_for_firmware(cover::test::scaled(milliseconds(30000))))
      << "PX4 did not connect to TCP " << config.port << "; console: " << px4.console_log();
  const double connect_s = seconds_since(started);

  PhysicsLoop physics(world, link);
  if (!lockstep) physics.pace_to_wall_clock();
  const auto monitor = FirmwareMonitor::px4(n);
  HoverStream stream(n, physics);
  ASSERT_TRUE(stream.opened());

  // Aligned: PX4 streams its attitude (vehicle_attitude is published once EKF2's tilt has
  // aligned) and its SYS_STATUS says the attitude estimate (AHRS) is healthy (a bit PX4 may
  // set before its checks have run: alone it is not enough). Until then the loop runs as
  // fast as PX4 answers (lockstep, unpaced).
  const auto ahrs_healthy = [&] {
    const auto status = monitor->sys_status();
    // PX4 reports the AHRS bit in health (and enabled), not in present.
    return status &&
           (status->onboard_control_sensors_health & mav::mav_sys_status_sensor::kAhrs) != 0 &&
           monitor->attitude().has_value();
  };
  const bool aligned = cover::test::wait_until(ahrs_healthy, milliseconds(120000), milliseconds(5));
  const double aligned_wall_s = seconds_since(started);
  const Truth at_alignment = physics.truth();
  const auto stats_at_alignment = link.stats();
  ASSERT_TRUE(aligned) << "PX4's AHRS never healthy; console: " << px4.console_log();
  const double boot_answers_per_s =
      static_cast<double>(stats_at_alignment.answers) / (aligned_wall_s - connect_s);
  physics.pace_to_wall_clock();
  const auto attitude = monitor->attitude();
  ASSERT_TRUE(attitude.has_value());
  // The estimate of the vehicle resting level: within 3 degrees of level.
  const Eigen::Quaterniond q_est(attitude->value.q1, attitude->value.q2, attitude->value.q3,
                                 attitude->value.q4);
  EXPECT_GT((q_est.normalized().toRotationMatrix().col(2)).z(), std::cos(3.0 * M_PI / 180.0));

  // OFFBOARD after a second of the (motors-off) stream; PX4 then says STANDBY once its
  // checks for that mode pass (without GPS its default Hold never does), then arm.
  ASSERT_TRUE(cover::test::wait_until([&] { return stream.sent() > 60; }, milliseconds(10000)));
  const auto mode = monitor->set_mode(mav::px4_mode::kMainOffboard);
  ASSERT_TRUE(mode.has_value());
  EXPECT_EQ(*mode, mav::mav_result::kAccepted);
  const bool ready = cover::test::wait_until(
      [&] {
        const auto hb = monitor->heartbeat();
        return hb && hb->system_status == mav::mav_state::kStandby;
      },
      milliseconds(60000), milliseconds(20));
  const double ready_wall_s = seconds_since(started);
  const double ready_firmware_s = physics.truth().firmware_time_s;
  ASSERT_TRUE(ready) << "PX4 never reported STANDBY in OFFBOARD; console: " << px4.console_log();
  const auto armed = monitor->command(mav::mav_cmd::kComponentArmDisarm, {1, 0, 0, 0, 0, 0, 0},
                                      cover::test::scaled(milliseconds(10000)));
  ASSERT_TRUE(armed.has_value());
  ASSERT_EQ(*armed, mav::mav_result::kAccepted) << "console: " << px4.console_log();
  ASSERT_TRUE(cover::test::wait_until([&] { return link.stats().armed; }, milliseconds(5000)))
      << "HIL_ACTUATOR_CONTROLS.mode never said armed";
  physics.release_deck();
  const auto stats_at_arm = link.stats();
  const auto px4_at_arm = link.px4_stats();
  const double firmware_at_arm = physics.truth().firmware_time_s;
  const auto wall_at_arm = std::chrono::steady_clock::now();
  stream.fly(true);

  // Climb, settle, then 10 s of hover (firmware time) measured on the truth.
  ASSERT_TRUE(cover::test::wait_until(
      [&] { return physics.truth().firmware_time_s > firmware_at_arm + 8.0; }, milliseconds(60000),
      milliseconds(20)))
      << "the firmware's clock stalled";
  double worst_altitude_error = 0.0;
  double sum_sq_altitude_error = 0.0;
  double worst_tilt_deg = 0.0;
  double worst_speed = 0.0;
  double worst_yaw_error_deg = 0.0;
  double worst_tilt_estimate_error_deg = 0.0;
  int samples = 0;
  const double hover_from = physics.truth().firmware_time_s;
  double last_t = 0.0;
  while (physics.truth().firmware_time_s < hover_from + 10.0) {
    const Truth t = physics.truth();
    if (t.firmware_time_s - last_t >= 0.01) {
      last_t = t.firmware_time_s;
      const double e = t.body.position_m.z - kHoverAltitudeM;
      worst_altitude_error = std::max(worst_altitude_error, std::abs(e));
      sum_sq_altitude_error += e * e;
      const double up_z = t.body.attitude.eigen().normalized().toRotationMatrix()(2, 2);
      worst_tilt_deg =
          std::max(worst_tilt_deg, std::acos(std::clamp(up_z, -1.0, 1.0)) * 180 / M_PI);
      worst_speed = std::max(worst_speed, t.body.velocity_m_s.eigen().norm());
      ++samples;
      // PX4's own attitude estimate against the truth (the frames' check: a wrong FRD or
      // NED conversion shows here first): heading and tilt.
      if (const auto estimate = monitor->attitude()) {
        const Eigen::Matrix3d r_est = Eigen::Quaterniond(estimate->value.q1, estimate->value.q2,
                                                         estimate->value.q3, estimate->value.q4)
                                          .normalized()
                                          .toRotationMatrix();
        const Eigen::Matrix3d r_true = t.body.attitude.eigen().normalized().toRotationMatrix();
        const double yaw_est_ned = std::atan2(r_est(1, 0), r_est(0, 0));
        const double yaw_true_ned = M_PI / 2.0 - std::atan2(r_true(1, 0), r_true(0, 0));
        const double yaw_error = std::remainder(yaw_est_ned - yaw_true_ned, 2.0 * M_PI);
        worst_yaw_error_deg = std::max(worst_yaw_error_deg, std::abs(yaw_error) * 180.0 / M_PI);
        const double tilt_est = std::acos(std::clamp(r_est(2, 2), -1.0, 1.0));
        const double tilt_true = std::acos(std::clamp(r_true(2, 2), -1.0, 1.0));
        worst_tilt_estimate_error_deg =
            std::max(worst_tilt_estimate_error_deg, std::abs(tilt_est - tilt_true) * 180.0 / M_PI);
      }
    }
    if (!px4.running()) break;
    std::this_thread::sleep_for(milliseconds(2));  // sampling the truth, not synchronising
  }
  const double wall_flying_s = seconds_since(wall_at_arm);
  const Truth end = physics.truth();
  const auto stats = link.stats();
  const auto px4_stats = link.px4_stats();
  const double firmware_flying_s = end.firmware_time_s - firmware_at_arm;
  const double answers_per_s =
      static_cast<double>(stats.answers - stats_at_arm.answers) / wall_flying_s;
  const double rms = std::sqrt(sum_sq_altitude_error / std::max(samples, 1));
  std::printf(
      "px4 hil (%s): connected %.2f s after start; aligned (attitude streamed, AHRS healthy) %.2f "
      "s wall after start, "
      "%.2f s firmware time, boot at %.0f answers/s; ready in OFFBOARD (STANDBY) %.2f s wall, "
      "%.2f s firmware; flying (paced): %.1f s firmware in %.1f s wall (real-time factor %.2f), "
      "%.0f answers/s; answers %llu, missed %llu, matched after arming %llu of %llu, time "
      "mismatches %llu, rejected %llu, free-run frames %llu, connections %llu; hover 10 s: "
      "altitude error rms %.3f m, max %.3f m, tilt max %.2f deg, speed max %.3f m/s; PX4's "
      "estimate vs truth: yaw %.2f deg, tilt %.2f deg at most; outputs %.3f %.3f %.3f %.3f\n",
      firmware_link::to_string(pacing), connect_s, aligned_wall_s, at_alignment.firmware_time_s,
      boot_answers_per_s, ready_wall_s, ready_firmware_s, firmware_flying_s, wall_flying_s,
      firmware_flying_s / wall_flying_s, answers_per_s,
      static_cast<unsigned long long>(stats.answers),
      static_cast<unsigned long long>(stats.answers_missed),
      static_cast<unsigned long long>(px4_stats.answers_matched - px4_at_arm.answers_matched),
      static_cast<unsigned long long>(stats.answers - stats_at_arm.answers),
      static_cast<unsigned long long>(px4_stats.answer_time_mismatches),
      static_cast<unsigned long long>(stats.frames_rejected),
      static_cast<unsigned long long>(px4_stats.free_run_frames),
      static_cast<unsigned long long>(px4_stats.connections), rms, worst_altitude_error,
      worst_tilt_deg, worst_speed, worst_yaw_error_deg, worst_tilt_estimate_error_deg,
      end.outputs[0], end.outputs[1], end.outputs[2], end.outputs[3]);

  EXPECT_TRUE(px4.running()) << "PX4 exited; console: " << px4.console_log();
  EXPECT_EQ(px4_stats.connections, 1U);
  EXPECT_GT(px4_stats.heartbeats, 0U);
  EXPECT_EQ(px4_stats.answer_time_mismatches, 0U);
  if (lockstep) {
    EXPECT_EQ(stats.answers_missed, 0U);
    // Every answer after arming is the one to the frame it followed.
    EXPECT_EQ(px4_stats.answers_matched - px4_at_arm.answers_matched,
              stats.answers - stats_at_arm.answers);
  } else {
    // A few ms per frame: PX4 keeps up on an idle machine; a loaded one may miss some.
    EXPECT_LT(stats.answers_missed - stats_at_arm.answers_missed,
              (stats.answers - stats_at_arm.answers) / 20);
  }
  EXPECT_EQ(stats.frames_rejected, 0U);
  EXPECT_GT(samples, 500);
  EXPECT_LT(worst_altitude_error, 0.3) << "rms " << rms;
  EXPECT_LT(worst_tilt_deg, 10.0);
  EXPECT_LT(worst_speed, 0.5);
  EXPECT_LT(worst_yaw_error_deg, 10.0);
  EXPECT_LT(worst_tilt_estimate_error_deg, 3.0);
  const auto hb = monitor->heartbeat();
  ASSERT_TRUE(hb.has_value());
  EXPECT_EQ(mav::px4_mode::main_mode(hb->custom_mode), mav::px4_mode::kMainOffboard);
  EXPECT_NE(hb->base_mode & 128, 0);

  stream.fly(false);
  physics.stop();  // PX4 waits for the next frame (it ignores SIGTERM there): stop kills it
  px4.stop(milliseconds(3000));
}

TEST_F(Px4Hil, BootsAlignsArmsAndHoversCoversPlantInLockstep) {
  boot_align_arm_and_hover(build(), Pacing::Lockstep);
}

TEST_F(Px4Hil, BootsAlignsArmsAndHoversCoversPlantInRealtime) {
  boot_align_arm_and_hover(build(), Pacing::Realtime);
}

}  // namespace
}  // namespace cover::firmware::test
