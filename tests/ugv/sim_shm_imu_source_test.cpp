#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <memory>
#include <optional>
#include <vector>

#include "cover/shm/segment.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/ugv/sim_shm_imu_source.hpp"
#include "ugv_test_support.hpp"

namespace {

using cover::shm::SeqlockWriter;
using cover::sim::kImuRingCapacity;
using cover::sim::SharedWorld;
using cover::test::append_sample;
using cover::test::trace_sample;
using cover::ugv::ImuSample;
using cover::ugv::ImuSourceState;
using cover::ugv::SimShmImuSource;
using namespace std::chrono_literals;

constexpr int kUgv = 3;

class SimShmImuSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    name_ = cover::shm::segment_name(0, cover::test::unique_run_id("imusrc"));
    writer_ =
        std::make_unique<SeqlockWriter<SharedWorld>>(name_, cover::sim::kWorldSegmentLayoutVersion);
  }
  void TearDown() override { cover::shm::remove_segment(name_); }

  void append(int first, int count, int ugv = kUgv) {
    for (int i = first; i < first + count; ++i) append_sample(*writer_, ugv, trace_sample(i));
  }

  // Reads until `count` samples arrived or a deadline passes.
  static std::vector<ImuSample> read_samples(SimShmImuSource& source, std::size_t count) {
    std::vector<ImuSample> all;
    std::vector<ImuSample> batch;
    const auto give_up = std::chrono::steady_clock::now() + 5s;
    while (all.size() < count && std::chrono::steady_clock::now() < give_up) {
      source.read(batch, 20ms);
      all.insert(all.end(), batch.begin(), batch.end());
    }
    return all;
  }

  static void expect_trace(const std::vector<ImuSample>& samples, int first) {
    for (std::size_t j = 0; j < samples.size(); ++j) {
      const ImuSample expected = trace_sample(first + static_cast<int>(j));
      ASSERT_EQ(samples[j].stamp_s, expected.stamp_s) << "sample " << j;
      EXPECT_EQ(samples[j].specific_force_m_s2, expected.specific_force_m_s2);
      EXPECT_EQ(samples[j].angular_velocity_rad_s, expected.angular_velocity_rad_s);
    }
  }

  std::string name_;
  std::unique_ptr<SeqlockWriter<SharedWorld>> writer_;
};

TEST_F(SimShmImuSourceTest, CarriesTheWheelSpeedReadWithASample) {
  SimShmImuSource source(name_, kUgv, 1s);
  ImuSample with = trace_sample(0);
  with.wheel_speed_m_s = -0.375;  // reversing: passed as is
  append_sample(*writer_, kUgv, with);
  append_sample(*writer_, kUgv, trace_sample(1));
  const std::vector<ImuSample> samples = read_samples(source, 2);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].wheel_speed_m_s, std::optional<double>(-0.375));
  EXPECT_FALSE(samples[1].wheel_speed_m_s.has_value());
}

TEST_F(SimShmImuSourceTest, DeliversExactlyTheWrittenSamplesInOrderNoneTwice) {
  SimShmImuSource source(name_, kUgv, 1s);
  EXPECT_EQ(source.describe(), "sim-shm:" + name_);
  append(0, 10);
  append(0, 7, /*ugv=*/1);  // another UGV's ring: not ours
  std::vector<ImuSample> first = read_samples(source, 10);
  ASSERT_EQ(first.size(), 10u);
  expect_trace(first, 0);

  append(10, 5);
  std::vector<ImuSample> second = read_samples(source, 5);
  ASSERT_EQ(second.size(), 5u);
  expect_trace(second, 10);

  // Nothing new (another UGV's write moves the sequence but adds nothing of ours).
  append(7, 1, /*ugv=*/1);
  std::vector<ImuSample> none;
  EXPECT_EQ(source.read(none, 30ms), 0u);
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(source.status().state, ImuSourceState::Ok);
  EXPECT_EQ(source.status().lost_samples, 0u);
}

TEST_F(SimShmImuSourceTest, ReadWaitsForItsTimeoutWhenNothingIsWritten) {
  SimShmImuSource source(name_, kUgv, 1s);
  std::vector<ImuSample> out;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(source.read(out, 40ms), 0u);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_GE(elapsed, 40ms);
  EXPECT_LT(elapsed, 1s);
}

TEST_F(SimShmImuSourceTest, AttachingLateDeliversTheRingWithoutCountingLoss) {
  append(0, 100);
  SimShmImuSource source(name_, kUgv, 1s);
  std::vector<ImuSample> samples = read_samples(source, kImuRingCapacity);
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(kImuRingCapacity));
  expect_trace(samples, 100 - kImuRingCapacity);
  EXPECT_EQ(source.status().lost_samples, 0u);
}

TEST_F(SimShmImuSourceTest, CountsLostSamplesWhenTheWriterRunsMoreThanARingAhead) {
  SimShmImuSource source(name_, kUgv, 1s);
  append(0, 3);
  ASSERT_EQ(read_samples(source, 3).size(), 3u);

  append(3, kImuRingCapacity + 10);  // 10 more than the ring holds since the last read
  std::vector<ImuSample> samples = read_samples(source, kImuRingCapacity);
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(kImuRingCapacity));
  expect_trace(samples, 13);  // resumes at the oldest sample still in the ring
  EXPECT_EQ(source.status().lost_samples, 10u);
  EXPECT_EQ(source.status().state, ImuSourceState::Ok);

  append(3 + kImuRingCapacity + 10, 2);  // and then carries on without further loss
  std::vector<ImuSample> after = read_samples(source, 2);
  ASSERT_EQ(after.size(), 2u);
  expect_trace(after, 3 + kImuRingCapacity + 10);
  EXPECT_EQ(source.status().lost_samples, 10u);
}

// A simulator that ends unlinks its world: the source ends (not an error).
TEST_F(SimShmImuSourceTest, EndsWhenTheWriterClosesItsSegment) {
  SimShmImuSource source(name_, kUgv, 1s);
  append(0, 2);
  ASSERT_EQ(read_samples(source, 2).size(), 2u);
  writer_.reset();  // unlinks the name; this (writer) process lives on
  std::vector<ImuSample> out;
  ASSERT_TRUE(cover::test::wait_until(
      [&] {
        source.read(out, 10ms);
        return source.status().state == ImuSourceState::Ended;
      },
      6s));  // the writer (this process) lives on: the source waits 3 s for it first
  EXPECT_NE(source.status().detail.find("closed"), std::string::npos) << source.status().detail;
  EXPECT_EQ(source.read(out, 10ms), 0u);
}

TEST_F(SimShmImuSourceTest, ReportsGoneWhenTheWriterProcessDies) {
  writer_.reset();
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // The simulator stand-in: publishes two samples, then waits to be killed. Killed, it
    // never unlinks the name, so only its pid tells that it is gone.
    SeqlockWriter<SharedWorld> writer(name_, cover::sim::kWorldSegmentLayoutVersion);
    append_sample(writer, kUgv, trace_sample(0));
    append_sample(writer, kUgv, trace_sample(1));
    const char byte = 1;
    if (write(ready[1], &byte, 1) != 1) _exit(1);
    pause();
    _exit(0);
  }
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1);
  SimShmImuSource source(name_, kUgv, 1s);
  ASSERT_EQ(read_samples(source, 2).size(), 2u);
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  std::vector<ImuSample> out;
  ASSERT_TRUE(cover::test::wait_until(
      [&] {
        source.read(out, 10ms);
        return source.status().state == ImuSourceState::Gone;
      },
      2s));
  EXPECT_NE(source.status().detail.find("died"), std::string::npos) << source.status().detail;
  // The dead writer cannot unlink its world: the reader that found it dead did.
  EXPECT_NE(access(cover::shm::segment_path(name_).c_str(), F_OK), 0);
  close(ready[0]);
  close(ready[1]);
}

TEST_F(SimShmImuSourceTest, TimesOutCleanlyWhenNoSegmentAppears) {
  const std::string missing = cover::shm::segment_name(0, cover::test::unique_run_id("absent"));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(SimShmImuSource(missing, kUgv, 200ms), std::runtime_error);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_GE(elapsed, 200ms);
  EXPECT_LT(elapsed, 5s);
}

TEST_F(SimShmImuSourceTest, RejectsAnIndexOutsideTheLayout) {
  EXPECT_THROW(SimShmImuSource(name_, cover::sim::kMaxUgvs, 1s), std::invalid_argument);
  EXPECT_THROW(SimShmImuSource(name_, -1, 1s), std::invalid_argument);
}

TEST_F(SimShmImuSourceTest, ReportsGoneForAUgvTheSimulatorDoesNotRun) {
  SimShmImuSource source(name_, kUgv, 1s);
  writer_->update([](SharedWorld& world) { world.ugv_count = 2; }, 0);
  std::vector<ImuSample> out;
  EXPECT_EQ(source.read(out, 50ms), 0u);
  EXPECT_EQ(source.status().state, ImuSourceState::Gone);
  EXPECT_NE(source.status().detail.find("no UGV 3"), std::string::npos);
}

}  // namespace
