// cover-ugv-agent as a real process: fed through a real shared-memory segment (or a CSV
// file), observed through real DDS on both vendors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/shm/segment.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/ugv_sensor_pipeline.hpp"
#include "cover/wire/sensors.hpp"
#include "ugv_test_support.hpp"

namespace {

using cover::dds::Vendor;
using cover::msg::UgvImu;
using cover::msg::UgvStatus;
using cover::process::ChildProcess;
using cover::shm::SeqlockWriter;
using cover::sim::SharedWorld;
using cover::test::trace_sample;
using cover::test::wait_until;
using namespace std::chrono_literals;

constexpr int kUgv = 2;
constexpr int kSigInt = 2;

// A domain of this test process's own (ctest runs test cases as parallel processes).
int private_domain() {
  return 100 + static_cast<int>(getpid() % 100);
}

// What the test expects on cover/ugv/k/imu: its own pipeline (filter and speed estimate)
// run on the same samples.
class ExpectedImu {
 public:
  void add(const cover::ugv::ImuSample& sample) {
    if (!cover::ugv::accepted(pipeline_.update(sample).imu_status)) return;
    by_seq_.push_back(cover::wire::to_msg(pipeline_.filter().output(), pipeline_.speed().estimate(),
                                          kUgv, seq_++));
  }
  std::size_t size() const { return by_seq_.size(); }
  const UgvImu& at(std::uint32_t seq) const { return by_seq_.at(seq); }

 private:
  cover::ugv::UgvSensorPipeline pipeline_{cover::ugv::ImuFilterParams::load_default(),
                                          cover::ugv::SpeedEstimatorParams::load_default()};
  std::uint32_t seq_ = 0;
  std::vector<UgvImu> by_seq_;
};

// Every UgvImu and UgvStatus the agent publishes, kept by seq / in order.
class Observer {
 public:
  explicit Observer(Vendor vendor) : participant_(options(vendor)) {
    imu_reader_ =
        participant_.make_reader(cover::dds::topics::ugv_imu(kUgv), [this](const UgvImu& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          imu_[m.seq] = m;
        });
    status_reader_ =
        participant_.make_reader(cover::dds::topics::ugv_status(kUgv), [this](const UgvStatus& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          status_.push_back(m);
        });
  }

  bool has_seq(std::uint32_t seq) {
    std::lock_guard<std::mutex> lock(mutex_);
    return imu_.count(seq) > 0;
  }
  std::map<std::uint32_t, UgvImu> imu() {
    std::lock_guard<std::mutex> lock(mutex_);
    return imu_;
  }
  // True once a status satisfying `condition` arrived.
  bool wait_for_status(const std::function<bool(const UgvStatus&)>& condition,
                       std::chrono::milliseconds timeout) {
    return wait_until(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const UgvStatus& s : status_) {
            if (condition(s)) return true;
          }
          return false;
        },
        timeout);
  }
  // The agent is up and matched both ways: its (reliable, transient-local) status arrived.
  bool wait_for_agent(std::chrono::milliseconds timeout) {
    return imu_reader_.wait_for_writers(1, timeout) &&
           wait_for_status([](const UgvStatus&) { return true; }, timeout);
  }

 private:
  static cover::dds::ParticipantOptions options(Vendor vendor) {
    cover::dds::ParticipantOptions o;
    o.vendor = vendor;
    o.domain_id = private_domain();
    return o;
  }

  cover::dds::Participant participant_;
  std::mutex mutex_;
  std::map<std::uint32_t, UgvImu> imu_;
  std::vector<UgvStatus> status_;
  cover::dds::Reader<UgvImu> imu_reader_;  // after what the callbacks use
  cover::dds::Reader<UgvStatus> status_reader_;
};

std::vector<std::string> agent_argv(Vendor vendor, std::vector<std::string> extra) {
  std::vector<std::string> argv{COVER_UGV_AGENT,
                                "--id",
                                std::to_string(kUgv),
                                "--dds",
                                cover::dds::vendor_name(vendor),
                                "--domain",
                                std::to_string(private_domain())};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return argv;
}

// Every received sample equals the expected one of its seq; the checks that matter.
void expect_equal_to_expected(const std::map<std::uint32_t, UgvImu>& received,
                              const ExpectedImu& expected) {
  for (const auto& [seq, m] : received) {
    ASSERT_LT(seq, expected.size()) << "seq beyond what the samples produce";
    EXPECT_EQ(m, expected.at(seq)) << "seq " << seq << " differs from the in-test filter";
  }
}

class UgvAgentProcess : public ::testing::TestWithParam<Vendor> {
 protected:
  void SetUp() override {
    run_id_ = cover::test::unique_run_id("agent");
    segment_ = cover::shm::segment_name(private_domain(), run_id_);
    writer_ = std::make_unique<SeqlockWriter<SharedWorld>>(segment_,
                                                           cover::sim::kWorldSegmentLayoutVersion);
    writer_->update([](SharedWorld& world) { world.ugv_count = cover::sim::kMaxUgvs; }, 0);
  }
  void TearDown() override { cover::shm::remove_segment(segment_); }

  // Writes sample i into the ring (and junk into another UGV's ring) and into `expected`.
  void feed(int i, ExpectedImu& expected) {
    cover::ugv::ImuSample sample = trace_sample(i);
    if (i == kFaultySample) sample.specific_force_m_s2.x() = std::nan("");
    if (i % 4 == 0) sample.wheel_speed_m_s = wheel_speed(i);  // 50 Hz odometry
    if (i == kFaultyOdometry) sample.wheel_speed_m_s = std::nan("");
    cover::test::append_sample(*writer_, kUgv, sample);
    cover::test::append_sample(*writer_, kUgv + 1, trace_sample(1000 + i));
    expected.add(sample);
  }

  static double wheel_speed(int i) { return 0.6 + 0.02 * std::sin(0.3 * i); }

  static constexpr int kFaultySample = 40;    // NaN: the agent's filter must reject it too
  static constexpr int kFaultyOdometry = 60;  // NaN wheel speed: the estimator rejects it
  std::string run_id_;
  std::string segment_;
  std::unique_ptr<SeqlockWriter<SharedWorld>> writer_;
};

TEST_P(UgvAgentProcess, PublishesExactlyWhatTheFilterComputesAndStopsOnSigint) {
  Observer observer(GetParam());
  ChildProcess agent(agent_argv(GetParam(), {"--run-id", run_id_}));
  ASSERT_TRUE(observer.wait_for_agent(20s)) << "the agent never came up on DDS";
  EXPECT_TRUE(observer.wait_for_status(
      [&](const UgvStatus& s) { return s.source == "sim-shm:" + segment_ && s.ugv_id == kUgv; },
      5s));

  // Lockstep, like the simulator: one sample, then wait for its filtered result.
  ExpectedImu expected;
  int missed = 0;
  constexpr int kLockstep = 120;
  for (int i = 0; i < kLockstep; ++i) {
    const std::size_t before = expected.size();
    feed(i, expected);
    if (expected.size() == before) continue;  // rejected: nothing to wait for
    const auto seq = static_cast<std::uint32_t>(expected.size() - 1);
    if (!wait_until([&] { return observer.has_seq(seq); }, 2s, 1ms)) ++missed;
  }
  // A burst, as when the agent is descheduled: it must catch up with every sample.
  constexpr int kBurst = 40;
  for (int i = kLockstep; i < kLockstep + kBurst; ++i) feed(i, expected);
  const auto last_seq = static_cast<std::uint32_t>(expected.size() - 1);
  EXPECT_TRUE(wait_until([&] { return observer.has_seq(last_seq); }, 5s));

  ASSERT_EQ(expected.size(), static_cast<std::size_t>(kLockstep + kBurst - 1));
  const auto received = observer.imu();
  expect_equal_to_expected(received, expected);
  EXPECT_LE(missed, 2) << "best-effort samples lost in lockstep";
  EXPECT_GE(received.size(), expected.size() * 9 / 10);
  // The published speed is the wheel odometry's, low-passed: sane, not just equal.
  const UgvImu& last = received.at(last_seq);
  EXPECT_EQ(last.speed_source, cover::msg::SpeedSource::SPEED_SOURCE_WHEEL_ODOMETRY);
  EXPECT_NEAR(last.speed_m_s, 0.6, 0.03);
  for (const auto& [seq, m] : received) EXPECT_TRUE(std::isfinite(m.speed_m_s)) << seq;

  EXPECT_TRUE(observer.wait_for_status(
      [&](const UgvStatus& s) {
        return s.samples == expected.size() && s.rejected_samples == 1 &&
               s.stamp_ns == expected.at(last_seq).stamp_ns;
      },
      3s))
      << "no heartbeat with the final counts";
  EXPECT_EQ(agent.terminate(5s, kSigInt), 0);
}

// The simulator ending (it unlinks its world) ends the agent cleanly: the end of a run.
TEST_P(UgvAgentProcess, ExitsZeroWhenTheSimulatorEnds) {
  Observer observer(GetParam());
  ChildProcess agent(agent_argv(GetParam(), {"--run-id", run_id_}));
  ASSERT_TRUE(observer.wait_for_agent(20s));
  writer_.reset();  // the simulator's segment disappears
  EXPECT_EQ(agent.wait(5s), std::optional<int>(0));
}

INSTANTIATE_TEST_SUITE_P(BothVendors, UgvAgentProcess,
                         ::testing::Values(Vendor::FastDds, Vendor::Cyclone),
                         [](const auto& info) { return std::string(vendor_name(info.param)); });

TEST(UgvAgentProcessCsv, ReplayPublishesItsSamplesAndExitsZero) {
  // With the optional wheel speed column, filled on the first 100 samples only.
  std::string text =
      "# replay test\nstamp_s,fx_m_s2,fy_m_s2,fz_m_s2,wx_rad_s,wy_rad_s,wz_rad_s,wheel_speed_m_s\n";
  ExpectedImu expected;
  constexpr int kSamples = 200;
  for (int i = 0; i < kSamples; ++i) {
    // Write with full precision and parse back: the agent sees exactly these doubles.
    cover::ugv::ImuSample s = trace_sample(i);
    char line[256];
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,", s.stamp_s,
                  s.specific_force_m_s2.x(), s.specific_force_m_s2.y(), s.specific_force_m_s2.z(),
                  s.angular_velocity_rad_s.x(), s.angular_velocity_rad_s.y(),
                  s.angular_velocity_rad_s.z());
    text += line;
    if (i < kSamples / 2) {
      s.wheel_speed_m_s = 0.5;
      text += "0.5";
    }
    text += "\n";
    expected.add(s);
  }
  const std::string path = cover::test::write_temp_file("agent_replay.csv", text);
  Observer observer(Vendor::Cyclone);
  ChildProcess agent(agent_argv(Vendor::Cyclone, {"--source", "csv", "--csv", path}));
  EXPECT_EQ(agent.wait(15s), std::optional<int>(0));  // 1 s of samples at real time
  ASSERT_TRUE(observer.wait_for_status(
      [&](const UgvStatus& s) { return s.source == "csv:" + path && s.samples == kSamples; }, 5s));
  const auto received = observer.imu();
  expect_equal_to_expected(received, expected);
  EXPECT_EQ(received.count(kSamples - 1), 1u) << "the last sample never arrived";
  ASSERT_TRUE(received.count(kSamples / 2 - 1)) << "the last sample with odometry never arrived";
  EXPECT_EQ(received.at(kSamples / 2 - 1).speed_source,
            cover::msg::SpeedSource::SPEED_SOURCE_WHEEL_ODOMETRY);
  EXPECT_EQ(received.at(kSamples / 2 - 1).speed_m_s, 0.5);
  // 0.5 s after the odometry stopped: the IMU's a_y / yaw_rate (about 0.1 / 0.35) or none.
  EXPECT_NE(received.at(kSamples - 1).speed_source,
            cover::msg::SpeedSource::SPEED_SOURCE_WHEEL_ODOMETRY);
  EXPECT_GE(received.size(), static_cast<std::size_t>(kSamples / 2));
}

TEST(UgvAgentProcessCli, UsageAndConfigErrorsExitTwo) {
  ChildProcess bad_id({COVER_UGV_AGENT, "--id", "99"});
  EXPECT_EQ(bad_id.wait(10s), std::optional<int>(2));
  ChildProcess no_id({COVER_UGV_AGENT});
  EXPECT_EQ(no_id.wait(10s), std::optional<int>(2));
  ChildProcess csv_without_file({COVER_UGV_AGENT, "--id", "0", "--source", "csv"});
  EXPECT_EQ(csv_without_file.wait(10s), std::optional<int>(2));
  const std::string typo =
      cover::test::write_temp_file("typo.yaml", "ugv_agent:\n  status_rate: 2\n");
  ChildProcess bad_config({COVER_UGV_AGENT, "--id", "0", "--config", typo});
  EXPECT_EQ(bad_config.wait(10s), std::optional<int>(2));
  ChildProcess help({COVER_UGV_AGENT, "--help"});
  EXPECT_EQ(help.wait(10s), std::optional<int>(0));
}

TEST(UgvAgentProcessCli, ExitsThreeWhenNoSegmentAppearsOrTheCsvIsMalformed) {
  const std::string quick =
      cover::test::write_temp_file("quick.yaml", "ugv_agent:\n  segment_wait_s: 0.3\n");
  ChildProcess no_segment({COVER_UGV_AGENT, "--id", "0", "--config", quick, "--domain",
                           std::to_string(private_domain()), "--run-id",
                           cover::test::unique_run_id("never")});
  EXPECT_EQ(no_segment.wait(10s), std::optional<int>(3));
  const std::string bad = cover::test::write_temp_file(
      "bad.csv", "stamp_s,fx_m_s2,fy_m_s2,fz_m_s2,wx_rad_s,wy_rad_s,wz_rad_s\n0,1,2\n");
  ChildProcess malformed({COVER_UGV_AGENT, "--id", "0", "--source", "csv", "--csv", bad, "--domain",
                          std::to_string(private_domain())});
  EXPECT_EQ(malformed.wait(10s), std::optional<int>(3));
}

}  // namespace
