// cover-sim's sensor-to-command latency: one sample per UAV and relative-state stamp (the
// direct path) or tick (through an autopilot), the first answer that names it
// (sim/app/latency/sensor_latency.hpp).
#include "latency/sensor_latency.hpp"

#include <gtest/gtest.h>

namespace cover::sim {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;
constexpr std::int64_t kMs = 1'000'000;

TEST(SensorLatency, TheFirstCommandNamingAStampIsItsSample) {
  SensorLatency latency(SensorLatency::kStampKeyStep);
  latency.published(kPeriodNs, 100 * kMs);
  EXPECT_TRUE(latency.answered(0, kPeriodNs, 100 * kMs + kMs / 4));
  ASSERT_EQ(latency.samples_ms().size(), 1U);
  EXPECT_DOUBLE_EQ(latency.samples_ms()[0], 0.25);
}

TEST(SensorLatency, CommandsStepOnTheSameStampAgainAreNotSamples) {
  // An agent with no new state steps again every 1.5 periods, naming the stamp it has.
  SensorLatency latency(SensorLatency::kStampKeyStep);
  latency.published(kPeriodNs, 0);
  EXPECT_TRUE(latency.answered(0, kPeriodNs, kMs / 4));
  EXPECT_FALSE(latency.answered(0, kPeriodNs, 15 * kMs));
  EXPECT_FALSE(latency.answered(0, kPeriodNs, 30 * kMs));
  EXPECT_EQ(latency.samples_ms().size(), 1U);
}

TEST(SensorLatency, EachUavAnswersForItself) {
  SensorLatency latency(SensorLatency::kStampKeyStep);
  latency.published(kPeriodNs, 0);
  EXPECT_TRUE(latency.answered(0, kPeriodNs, kMs));
  EXPECT_TRUE(latency.answered(1, kPeriodNs, 2 * kMs));
  EXPECT_EQ(latency.samples_ms().size(), 2U);
}

TEST(SensorLatency, AStampPublishedAgainIsAnsweredAgain) {
  SensorLatency latency(SensorLatency::kStampKeyStep);
  latency.published(kPeriodNs, 0);
  EXPECT_TRUE(latency.answered(0, kPeriodNs, kMs));
  latency.published(kPeriodNs, 5 * kMs);  // a republished tick: a new measurement
  EXPECT_TRUE(latency.answered(0, kPeriodNs, 6 * kMs));
  EXPECT_DOUBLE_EQ(latency.samples_ms().back(), 1.0);
}

TEST(SensorLatency, UnknownForgottenOrBadStampsAndUavsAreNotSamples) {
  SensorLatency latency(SensorLatency::kStampKeyStep);
  latency.published(kPeriodNs, 0);
  EXPECT_FALSE(latency.answered(0, 2 * kPeriodNs, kMs));  // never published
  EXPECT_FALSE(latency.answered(-1, kPeriodNs, kMs));
  EXPECT_FALSE(latency.answered(fleet::kMaxUavs, kPeriodNs, kMs));
  EXPECT_FALSE(latency.answered(0, -kPeriodNs, kMs));
  EXPECT_FALSE(latency.answered(0, 0, kMs));
  // 256 ms later the slot holds another stamp: the old one is forgotten.
  latency.published(kPeriodNs + 256 * kMs, kMs);
  EXPECT_FALSE(latency.answered(0, kPeriodNs, 2 * kMs));
  EXPECT_TRUE(latency.samples_ms().empty());
}

TEST(SensorLatency, TicksAsKeysEachHaveTheirOwnSlot) {
  // The autopilot path names a tick (a setpoint's time_boot_ms over the period).
  SensorLatency latency(SensorLatency::kTickKeyStep);
  for (std::int64_t tick = 1; tick <= 256; ++tick) latency.published(tick, tick * kPeriodNs);
  for (std::int64_t tick = 1; tick <= 256; ++tick) {
    EXPECT_TRUE(latency.answered(0, tick, tick * kPeriodNs + kMs)) << tick;
    EXPECT_FALSE(latency.answered(0, tick, tick * kPeriodNs + 2 * kMs)) << tick;
  }
  ASSERT_EQ(latency.samples_ms().size(), 256U);
  for (const double sample_ms : latency.samples_ms()) EXPECT_DOUBLE_EQ(sample_ms, 1.0);
  latency.published(257, 0);  // takes tick 1's slot
  EXPECT_FALSE(latency.answered(1, 1, kMs));
}

}  // namespace
}  // namespace cover::sim
