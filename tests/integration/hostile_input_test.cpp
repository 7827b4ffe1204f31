// Hostile samples fed into a running UAV agent while it flies (issue 13, item 4): a DDS
// writer on its input topics publishes NaN, infinite, out-of-range, foreign-id, stale and
// future-stamped relative states and UGV IMU samples beside the simulator's real ones. The
// agent must drop every one of them (its status counts them, its log names them at a
// limited rate), keep its commands finite and inside the input boxes, and still land.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "process_support.hpp"
#include "sim_system.hpp"

namespace {

using cover::test::bin;
using namespace std::chrono_literals;
using cover::sim::SharedWorld;
using Clock = std::chrono::steady_clock;
namespace msg = cover::msg;

constexpr int kDomain = 130;  // apart from every other test and benchmark
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using cover::test::read_text;
using cover::test::scaled;

// Every command the agent sends, checked as it arrives.
class CommandCheck {
 public:
  explicit CommandCheck(cover::dds::Participant& p)
      : reader_(p.make_reader(cover::dds::topics::uav_command(0), [this](const msg::UavCommand& c) {
          std::lock_guard<std::mutex> lock(mutex_);
          ++count_;
          const auto& w = c.body_rates_rad_s;
          const bool finite = std::isfinite(c.thrust_m_s2) && std::isfinite(w.x) &&
                              std::isfinite(w.y) && std::isfinite(w.z);
          // sampc.yaml's input boxes: thrust 2..20 m/s^2 (0 disarmed), rates +-3.14 / +-1.5.
          const bool bounded = c.thrust_m_s2 >= 0.0 && c.thrust_m_s2 <= 20.0 + 1e-9 &&
                               std::abs(w.x) <= 3.14 + 1e-9 && std::abs(w.y) <= 3.14 + 1e-9 &&
                               std::abs(w.z) <= 1.5 + 1e-9;
          if (!finite || !bounded) ++bad_;
        })) {}
  std::uint64_t count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }
  std::uint64_t bad() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return bad_;
  }

 private:
  mutable std::mutex mutex_;
  std::uint64_t count_ = 0;
  std::uint64_t bad_ = 0;
  cover::dds::Reader<msg::UavCommand> reader_;
};

msg::RelativeState hostile_state(int kind, std::uint32_t ugv, std::int64_t now_ns) {
  msg::RelativeState s;
  s.uav_id = 0;
  s.ugv_id = ugv;
  s.stamp_ns = now_ns;
  s.position_m = {0.0, 0.0, 1.0};
  s.attitude = {1.0, 0.0, 0.0, 0.0};
  s.valid = true;
  switch (kind) {
    case 0:
      s.position_m.z = kNaN;
      break;
    case 1:
      s.velocity_m_s.x = kInf;
      break;
    case 2:
      s.position_m.x = 1e6;  // out of range
      break;
    case 3:
      s.attitude = {2.0, 0.0, 0.0, 0.0};  // not a rotation
      break;
    case 4:
      s.ugv_id = ugv + 7;  // another UGV's state on this topic
      break;
    case 5:
      s.stamp_ns = now_ns + 3'600'000'000'000;  // an hour ahead
      break;
    default:
      s.stamp_ns = now_ns - 5'000'000'000;  // 5 s old: older than what the agent has
      break;
  }
  return s;
}

msg::UgvImu hostile_imu(int kind, std::uint32_t ugv, std::int64_t now_ns) {
  msg::UgvImu s;
  s.ugv_id = ugv;
  s.stamp_ns = now_ns;
  s.specific_force_m_s2 = {0.0, 0.0, 9.81};
  switch (kind) {
    case 0:
      s.angular_velocity_rad_s.z = kNaN;
      break;
    case 1:
      s.specific_force_m_s2.z = 1e5;
      break;
    case 2:
      s.ugv_id = ugv + 3;
      break;
    default:
      s.stamp_ns = now_ns + 3'600'000'000'000;
      break;
  }
  return s;
}

std::size_t count_of(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

TEST(HostileInput, BadSamplesAreDroppedCountedAndNeverCommanded) {
  cover::test::SimSystem system(kDomain, "hi", {"--scenario", "scenario2"}, "realtime",
                                scaled(20s));
  auto uav =
      system.spawn({bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "2",
                    "--task", std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml"},
                   "uav");

  cover::dds::ParticipantOptions options;
  options.domain_id = kDomain;
  {
    cover::dds::Participant attacker(options);
    CommandCheck commands(attacker);
    auto status = attacker.make_reader(cover::dds::topics::uav_status(0));
    auto task_status = attacker.make_reader(cover::dds::topics::task_status());
    std::vector<cover::dds::Writer<msg::RelativeState>> states;
    std::vector<cover::dds::Writer<msg::UgvImu>> imus;
    for (std::uint32_t k = 0; k < 2; ++k) {
      states.push_back(attacker.make_writer(cover::dds::topics::relative_state(0, k)));
      imus.push_back(attacker.make_writer(cover::dds::topics::ugv_imu(k)));
    }
    for (auto& w : states) ASSERT_TRUE(w.wait_for_readers(1, scaled(30s)));
    for (auto& w : imus) ASSERT_TRUE(w.wait_for_readers(1, scaled(30s)));
    ASSERT_TRUE(status.wait_for_sample(scaled(30s)));

    // Airborne under the agent's commands, then 3 s of hostile samples at ~500 Hz.
    ASSERT_TRUE(system.wait_for_world(
        [](const SharedWorld& w) { return w.uavs[0].state.position_m.z > 1.0; }, 30s))
        << "the UAV never took off";
    auto copy = std::make_unique<SharedWorld>();
    std::uint64_t sent = 0;
    const auto flood_end = Clock::now() + 3s;
    for (int i = 0; Clock::now() < flood_end; ++i) {
      ASSERT_TRUE(system.read_world(*copy));
      const auto now_ns = static_cast<std::int64_t>(std::llround(copy->time_s * 1e9));
      const auto k = static_cast<std::uint32_t>(i % 2);
      states[k].write(hostile_state(i % 7, k, now_ns));
      imus[k].write(hostile_imu(i % 4, k, now_ns));
      sent += 2;
      std::this_thread::sleep_for(2ms);  // pacing the ~500 Hz flood, not synchronisation
    }
    ASSERT_GT(sent, 1000u);
    // The status (10 Hz) counts what was dropped: most of the flood (best-effort sensor
    // QoS may lose some; a future stamp is judged only if it is the newest at a step).
    std::uint32_t rejected = 0;
    cover::test::wait_until(
        [&] {
          rejected = status.latest()->sample.rejected_samples;
          return rejected >= sent / 2;
        },
        5s, 50ms);
    EXPECT_GE(rejected, sent / 2) << "sent " << sent;
    EXPECT_LE(rejected, sent);
    // Still the task it was flying: to the end, landed on G1.
    std::optional<msg::TaskStatus> ended;
    cover::test::wait_until(
        [&] {
          const auto latest = task_status.latest();
          if (latest && (latest->sample.state == msg::TaskState::TASK_SUCCEEDED ||
                         latest->sample.state == msg::TaskState::TASK_FAILED)) {
            ended = latest->sample;
          }
          return ended.has_value();
        },
        60s, 50ms);
    ASSERT_TRUE(ended) << "the task never ended";
    EXPECT_EQ(ended->state, msg::TaskState::TASK_SUCCEEDED) << ended->message;
    std::cout << "hostile samples sent " << sent << ", rejected (agent's count) " << rejected
              << ", commands " << commands.count() << ", bad commands " << commands.bad() << "\n";
    EXPECT_GT(commands.count(), 1000u);
    EXPECT_EQ(commands.bad(), 0u) << "non-finite or out-of-box commands";
  }
  EXPECT_EQ(uav->terminate(scaled(10s), SIGINT), 0);
  system.sim().terminate(scaled(10s), SIGINT);
  for (auto& ugv : system.ugvs()) ugv->wait(scaled(10s));
  // Named by reason and topic, at most one line per reason per second (4 reasons here
  // per topic kind, ~40 s of flight at most): a flood of samples is not a flood of lines.
  const std::string log = read_text(system.log_path("uav"));
  for (const char* reason : {"non-finite", "out-of-range", "unknown-id"}) {
    EXPECT_NE(log.find(std::string(": ") + reason + " (rejected so far"), std::string::npos)
        << reason << "\n"
        << log;
  }
  EXPECT_LT(count_of(log, "dropped a sample"), 5u * 45u) << log;
}

}  // namespace
