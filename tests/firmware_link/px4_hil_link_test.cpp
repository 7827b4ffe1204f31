// Px4HilLink against an in-process fake PX4 on loopback TCP: a client that connects to the
// link's port as simulator_mavlink does, says HEARTBEAT, and answers HIL_SENSOR frames with
// HIL_ACTUATOR_CONTROLS of the frame's time (after a boot of a few unanswered frames),
// optionally leaving one unanswered, writing garbage, or reconnecting. The plant is a World
// with the motor-level UAV (config/sim/firmware_uav_px4.yaml).
#include "cover/firmware_link/px4_hil_link.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "cover/config/yaml_reader.hpp"
#include "cover/mavlink/hil_messages.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/sim/world.hpp"
#include "cover/test/time_scale.hpp"

namespace cover::firmware_link {
namespace {

using std::chrono::milliseconds;

struct FakePx4Options {
  int boot_frames = 3;       // frames left unanswered while "booting"
  int silent_frame = -1;     // this frame (0-based) gets no answer
  int garbage_before = -1;   // garbage bytes are written before this frame's answer
  int reconnect_after = -1;  // drop the connection after this many frames, connect again
};

struct SeenSensor {
  std::uint64_t time_usec = 0;
  std::uint32_t fields_updated = 0;
  int connection = 0;
};

class FakePx4 {
 public:
  FakePx4(std::uint16_t port, FakePx4Options options) : port_(port), options_(options) {
    thread_ = std::thread([this] { run(); });
  }
  ~FakePx4() {
    stop_ = true;
    thread_.join();
  }
  std::vector<SeenSensor> sensors() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return sensors_;
  }
  int ground_truth_frames() const { return ground_truth_; }

 private:
  void run() {
    int frames = 0;
    for (int connection = 1; !stop_ && connection <= 2; ++connection) {
      auto link = mavlink::make_link(
          mavlink::ConnectionUrl::parse("tcp://127.0.0.1:" + std::to_string(port_)));
      while (!stop_ && !link->open()) std::this_thread::sleep_for(milliseconds(1));  // PX4 retries
      mavlink::Encoder encoder(2, 1);
      mavlink::Heartbeat hello;
      hello.autopilot = 12;
      send(*link, encoder.encode(hello));
      mavlink::StreamParser parser;
      std::array<std::uint8_t, 4096> buffer{};
      bool dropped = false;
      while (!stop_ && !dropped && link->is_open()) {
        const std::size_t n = link->read(buffer.data(), buffer.size(), milliseconds(10));
        parser.feed(buffer.data(), n, [&](const mavlink::Frame& f) {
          if (mavlink::decode<mavlink::HilStateQuaternion>(f)) ++ground_truth_;
          const auto sensor = mavlink::decode<mavlink::HilSensor>(f);
          if (!sensor || dropped) return;
          {
            std::lock_guard<std::mutex> lock(mutex_);
            sensors_.push_back({sensor->time_usec, sensor->fields_updated, connection});
          }
          const int index = frames++;
          const int in_connection = static_cast<int>(
              std::count_if(sensors_.begin(), sensors_.end(),
                            [&](const SeenSensor& s) { return s.connection == connection; }));
          if (in_connection <= options_.boot_frames || index == options_.silent_frame) return;
          if (index == options_.garbage_before) {
            const std::array<std::uint8_t, 40> garbage{0xFD, 0x51, 0x00, 0x00, 0x07, 0xFD, 0x01};
            link->write(garbage.data(), garbage.size());
          }
          mavlink::HilActuatorControls answer;
          answer.time_usec = sensor->time_usec;
          answer.flags = mavlink::kHilActuatorControlsLockstep;
          answer.controls = {0.25F, 0.5F, 0.75F, 2.0F};  // 2.0: clamped to 1
          answer.mode = 129;
          send(*link, encoder.encode(answer));
          if (index + 1 == options_.reconnect_after && connection == 1) {
            link->close();
            dropped = true;
          }
        });
      }
      if (!dropped) return;
    }
  }
  static void send(mavlink::Link& link, const mavlink::EncodedFrame& frame) {
    link.write(frame.bytes.data(), frame.size);
  }

  std::uint16_t port_;
  FakePx4Options options_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::vector<SeenSensor> sensors_;
  std::atomic<int> ground_truth_{0};
  std::thread thread_;
};

sim::World plant() {
  const std::string dir = config::default_config_dir() + "/sim/";
  sim::WorldParams params = sim::WorldParams::load_file(dir + "world_default.yaml");
  params.uav_initial.start_on_ugv = -1;
  return sim::World(params, sim::FirmwareUavParams::load_file(dir + "firmware_uav_px4.yaml",
                                                              params.physics_rate_hz));
}

// Steps the world `steps` times, exchanging each step.
sim::MotorOutputs run(sim::World& world, Px4HilLink& link, int steps) {
  sim::MotorOutputs outputs{};
  for (int i = 0; i < steps; ++i) {
    world.settle_uav(outputs);
    outputs = link.exchange(plant_sample(world.motor_uav(), world.state().uav));
  }
  return outputs;
}

Px4HilConfig test_config(Pacing pacing) {
  Px4HilConfig config;
  config.port = 0;
  config.pacing = pacing;
  config.lockstep_timeout = cover::test::scaled(milliseconds(2000));
  return config;
}

TEST(Px4HilLink, BootsFreeRunningThenWaitsForEachAnswer) {
  Px4HilLink link(test_config(Pacing::Lockstep));
  ASSERT_GT(link.port(), 0);
  FakePx4 px4(link.port(), {});
  ASSERT_TRUE(link.wait_for_firmware(cover::test::scaled(milliseconds(5000))));
  sim::World world = plant();
  const sim::MotorOutputs outputs = run(world, link, 400);  // 0.4 s: 100 IMU frames

  const auto seen = px4.sensors();
  ASSERT_EQ(seen.size(), 100U);
  std::uint64_t previous = 0;
  int with_mag = 0;
  int with_baro = 0;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].time_usec, 4000U * (i + 1)) << i;  // the firmware's clock, never 0
    EXPECT_GT(seen[i].time_usec, previous);
    previous = seen[i].time_usec;
    EXPECT_EQ(seen[i].fields_updated & 63U, 63U);
    with_mag += (seen[i].fields_updated & 448U) == 448U ? 1 : 0;
    with_baro += (seen[i].fields_updated & 6656U) == 6656U ? 1 : 0;
  }
  EXPECT_EQ(with_mag, 40);                   // 100 Hz: every sample rides on the next IMU frame
  EXPECT_EQ(with_baro, 20);                  // 50 Hz
  EXPECT_GE(px4.ground_truth_frames(), 19);  // 50 Hz of firmware time
  EXPECT_LE(px4.ground_truth_frames(), 21);

  const FirmwareLinkStats stats = link.stats();
  const Px4HilStats px4_stats = link.px4_stats();
  EXPECT_EQ(px4_stats.free_run_frames, 4U);  // 3 unanswered, the 4th's answer ends the boot
  EXPECT_EQ(stats.answers, 97U);
  // The boot's last answer may come while the next frame is paced (nothing awaited yet).
  EXPECT_GE(px4_stats.answers_matched, 96U);
  EXPECT_EQ(stats.answers_missed, 0U);
  EXPECT_EQ(px4_stats.answer_time_mismatches, 0U);
  EXPECT_EQ(px4_stats.heartbeats, 1U);
  EXPECT_EQ(px4_stats.connections, 1U);
  EXPECT_EQ(stats.frames_rejected, 0U);
  EXPECT_TRUE(stats.armed);
  EXPECT_EQ(outputs, (sim::MotorOutputs{0.25, 0.5, 0.75, 1.0}));
}

TEST(Px4HilLink, CountsAMissedAnswerAndGarbageAndGoesOn) {
  Px4HilConfig config = test_config(Pacing::Lockstep);
  config.lockstep_timeout = milliseconds(100);
  Px4HilLink link(config);
  FakePx4Options options;
  options.silent_frame = 30;
  options.garbage_before = 20;
  FakePx4 px4(link.port(), options);
  ASSERT_TRUE(link.wait_for_firmware(cover::test::scaled(milliseconds(5000))));
  sim::World world = plant();
  const auto started = std::chrono::steady_clock::now();
  run(world, link, 200);
  const double waited_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const FirmwareLinkStats stats = link.stats();
  EXPECT_EQ(stats.answers_missed, 1U);
  EXPECT_GE(waited_s, 0.1);  // the missed answer was waited for, bounded
  EXPECT_EQ(stats.answers, 50U - 3U - 1U);
  EXPECT_GT(stats.frames_rejected + link.px4_stats().parser.garbage_bytes, 0U);
  EXPECT_EQ(link.px4_stats().answer_time_mismatches, 0U);
}

TEST(Px4HilLink, APx4ThatReconnectsBootsAgain) {
  Px4HilLink link(test_config(Pacing::Lockstep));
  FakePx4Options options;
  options.reconnect_after = 20;
  FakePx4 px4(link.port(), options);
  ASSERT_TRUE(link.wait_for_firmware(cover::test::scaled(milliseconds(5000))));
  sim::World world = plant();
  run(world, link, 400);
  const auto stats = link.px4_stats();
  EXPECT_EQ(stats.connections, 2U);
  EXPECT_EQ(stats.heartbeats, 2U);
  EXPECT_GE(stats.free_run_frames, 8U);  // two boots
  EXPECT_EQ(link.stats().answers_missed, 0U);
  const auto seen = px4.sensors();
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back().connection, 2);
  EXPECT_GT(link.stats().answers, 80U);
}

TEST(Px4HilLink, APortAlreadyHeldIsAnErrorAtConstruction) {
  Px4HilLink first(test_config(Pacing::Lockstep));
  Px4HilConfig config = test_config(Pacing::Lockstep);
  config.port = first.port();
  EXPECT_THROW(Px4HilLink second(config), std::runtime_error);
}

TEST(Px4HilLink, RealtimeWaitsOnlyBrieflyForAnAnswer) {
  Px4HilConfig config = test_config(Pacing::Realtime);
  config.realtime_timeout = milliseconds(4);
  Px4HilLink link(config);
  FakePx4Options options;
  options.silent_frame = 10;
  FakePx4 px4(link.port(), options);
  ASSERT_TRUE(link.wait_for_firmware(cover::test::scaled(milliseconds(5000))));
  sim::World world = plant();
  run(world, link, 200);
  EXPECT_EQ(link.stats().answers_missed, 1U);
  EXPECT_EQ(link.stats().answers, 50U - 3U - 1U);
}

}  // namespace
}  // namespace cover::firmware_link
