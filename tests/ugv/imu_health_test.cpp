#include <gtest/gtest.h>

#include <cstdint>

#include "cover/ugv/imu_health.hpp"

namespace {

using cover::ugv::ImuHealthMonitor;

constexpr std::int64_t kMs = 1'000'000;

// Feeds one second of samples at `rate_hz`, the first `rejected` of them rejected.
std::int64_t feed_second(ImuHealthMonitor& monitor, std::int64_t start_ns, int rate_hz,
                         int rejected = 0) {
  const std::int64_t period_ns = 1000 * kMs / rate_hz;
  for (int i = 0; i < rate_hz; ++i) monitor.on_sample(start_ns + i * period_ns, i >= rejected);
  return start_ns + rate_hz * period_ns;
}

TEST(ImuHealth, HealthyAtTheNominalRate) {
  ImuHealthMonitor monitor(200.0);
  EXPECT_FALSE(monitor.evaluate(0).healthy);
  const std::int64_t end = feed_second(monitor, 0, 200);
  const auto health = monitor.evaluate(end - kMs);
  EXPECT_TRUE(health.healthy);
  EXPECT_DOUBLE_EQ(health.imu_rate_hz, 200.0);
}

TEST(ImuHealth, UnhealthyBelowEightyPercentOfNominal) {
  ImuHealthMonitor monitor(200.0);
  const std::int64_t end = feed_second(monitor, 0, 150);
  const auto health = monitor.evaluate(end - kMs);
  EXPECT_FALSE(health.healthy);
  EXPECT_NEAR(health.imu_rate_hz, 150.0, 1e-9);
  ImuHealthMonitor just_enough(200.0);
  EXPECT_TRUE(just_enough.evaluate(feed_second(just_enough, 0, 160) - kMs).healthy);
}

TEST(ImuHealth, UnhealthyWhenTheFilterRejectsMoreThanAFifth) {
  ImuHealthMonitor monitor(200.0);
  const std::int64_t end = feed_second(monitor, 0, 200, /*rejected=*/50);
  EXPECT_FALSE(monitor.evaluate(end - kMs).healthy);
  ImuHealthMonitor few(200.0);
  EXPECT_TRUE(few.evaluate(feed_second(few, 0, 200, /*rejected=*/10) - kMs).healthy);
}

TEST(ImuHealth, AStalledDeviceTurnsUnhealthyWithinASecond) {
  ImuHealthMonitor monitor(200.0);
  const std::int64_t end = feed_second(monitor, 0, 200);
  ASSERT_TRUE(monitor.evaluate(end).healthy);
  const auto stalled = monitor.evaluate(end + 1000 * kMs);
  EXPECT_FALSE(stalled.healthy);
  EXPECT_EQ(stalled.imu_rate_hz, 0.0);
  // and recovers when samples come back, rejections having left the window
  feed_second(monitor, end + 1000 * kMs, 200);
  EXPECT_TRUE(monitor.evaluate(end + 1995 * kMs).healthy);
}

}  // namespace
