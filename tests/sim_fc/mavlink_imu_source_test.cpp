// cover-ugv-agent's MAVLink IMU source over a real UDP socket, fed by our Encoder as a
// UGV's autopilot would: FRD -> FLU, the stamps, SCALED_IMU's units, repeats and other
// systems.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cover/clock/clock.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/ugv/mavlink_imu_source.hpp"
#include "test_support.hpp"

namespace {

using cover::sim::fc::test::free_port_base;
using cover::ugv::ImuSample;
using cover::ugv::MavlinkImuSource;
using cover::ugv::MavlinkStamp;
namespace mav = cover::mavlink;
using namespace std::chrono_literals;

// A UGV autopilot sending to the source's udpin port.
class Autopilot {
 public:
  explicit Autopilot(std::uint16_t port, std::uint8_t system = 101)
      : link_(mav::make_link(
            mav::ConnectionUrl::parse("udpout://127.0.0.1:" + std::to_string(port)))),
        encoder_(system, 1) {
    EXPECT_TRUE(link_->open());
  }
  template <typename M>
  void send(const M& message) {
    const auto frame = encoder_.encode(message);
    ASSERT_TRUE(link_->write(frame.bytes.data(), frame.size));
  }

 private:
  std::unique_ptr<mav::Link> link_;
  mav::Encoder encoder_;
};

mav::HighresImu highres(std::uint64_t time_usec, float ax, float ay, float az, float gz) {
  mav::HighresImu imu;
  imu.time_usec = time_usec;
  imu.xacc = ax;
  imu.yacc = ay;
  imu.zacc = az;
  imu.xgyro = 0.01F;
  imu.ygyro = 0.02F;
  imu.zgyro = gz;
  imu.fields_updated = 0x3F;
  return imu;
}

// Reads until `count` samples came (or a deadline).
std::vector<ImuSample> read_samples(MavlinkImuSource& source, std::size_t count) {
  std::vector<ImuSample> all;
  std::vector<ImuSample> batch;
  const auto deadline = std::chrono::steady_clock::now() + cover::sim::fc::test::scaled(3s);
  while (all.size() < count && std::chrono::steady_clock::now() < deadline) {
    source.read(batch, 50ms);
    all.insert(all.end(), batch.begin(), batch.end());
  }
  return all;
}

TEST(MavlinkImuSource, HighresImuFrdBecomesFluStampedWithTheAutopilotsTime) {
  const auto port = free_port_base(1);
  const std::string url = "udpin://127.0.0.1:" + std::to_string(port);
  MavlinkImuSource source(url, MavlinkStamp::Autopilot);
  EXPECT_EQ(source.describe(), "mavlink:" + url);
  Autopilot autopilot(port);
  autopilot.send(highres(5000, 0.5F, 0.25F, -9.81F, -0.35F));
  autopilot.send(highres(5000, 0.5F, 0.25F, -9.81F, -0.35F));  // a repeat
  autopilot.send(highres(10000, 0.5F, 0.25F, -9.81F, -0.35F));
  autopilot.send(highres(7500, 0.0F, 0.0F, -9.81F, std::nanf("")));  // older: the filter's
  mav::HighresImu second_imu = highres(20000, 1, 1, 1, 1);
  second_imu.id = 1;  // another IMU of the same autopilot
  autopilot.send(second_imu);
  Autopilot other(port, 102);
  other.send(highres(30000, 1, 1, 1, 1));  // another system on the link

  const auto samples = read_samples(source, 3);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(cover::clock::s_to_ns(samples[0].stamp_s), 5'000'000);
  EXPECT_EQ(cover::clock::s_to_ns(samples[1].stamp_s), 10'000'000);
  EXPECT_EQ(cover::clock::s_to_ns(samples[2].stamp_s), 7'500'000);
  EXPECT_TRUE(std::isnan(samples[2].angular_velocity_rad_s.z()));
  const ImuSample& s = samples[0];
  EXPECT_FLOAT_EQ(s.specific_force_m_s2.x(), 0.5F);
  EXPECT_FLOAT_EQ(s.specific_force_m_s2.y(), -0.25F);
  EXPECT_FLOAT_EQ(s.specific_force_m_s2.z(), 9.81F);  // at rest: +g up in FLU
  EXPECT_FLOAT_EQ(s.angular_velocity_rad_s.x(), 0.01F);
  EXPECT_FLOAT_EQ(s.angular_velocity_rad_s.y(), -0.02F);
  EXPECT_FLOAT_EQ(s.angular_velocity_rad_s.z(), 0.35F);  // a left turn
  EXPECT_FALSE(s.wheel_speed_m_s);
  EXPECT_EQ(source.repeats(), 1u);
  EXPECT_EQ(source.imu_system(), 101);
  EXPECT_EQ(read_samples(source, 1).size(), 0u);  // IMU 1 and system 102 were not taken
}

TEST(MavlinkImuSource, ScaledImuOnlyWhileThereIsNoHighresImu) {
  const auto port = free_port_base(1);
  MavlinkImuSource source("udpin://127.0.0.1:" + std::to_string(port), MavlinkStamp::Autopilot);
  Autopilot autopilot(port);
  mav::ScaledImu scaled;
  scaled.time_boot_ms = 1500;
  scaled.xacc = 100;    // mG
  scaled.zacc = -1000;  // -1 g along FRD z: at rest
  scaled.zgyro = -350;  // mrad/s
  autopilot.send(scaled);
  const auto first = read_samples(source, 1);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_DOUBLE_EQ(first[0].stamp_s, 1.5);
  EXPECT_NEAR(first[0].specific_force_m_s2.x(), 0.980665, 1e-9);
  EXPECT_NEAR(first[0].specific_force_m_s2.z(), 9.80665, 1e-9);
  EXPECT_NEAR(first[0].angular_velocity_rad_s.z(), 0.35, 1e-9);
  autopilot.send(highres(2'000'000, 0, 0, -9.8F, 0));
  scaled.time_boot_ms = 2500;
  autopilot.send(scaled);  // HIGHRES_IMU is heard now: ignored
  autopilot.send(highres(3'000'000, 0, 0, -9.8F, 0));
  const auto later = read_samples(source, 2);
  ASSERT_EQ(later.size(), 2u);
  EXPECT_DOUBLE_EQ(later[0].stamp_s, 2.0);
  EXPECT_DOUBLE_EQ(later[1].stamp_s, 3.0);
}

TEST(MavlinkImuSource, ReceiveStampsAreTheHostsSystemClock) {
  const auto port = free_port_base(1);
  MavlinkImuSource source("udpin://127.0.0.1:" + std::to_string(port), MavlinkStamp::Receive);
  Autopilot autopilot(port);
  const double before_s = cover::clock::system_s();
  autopilot.send(highres(5000, 0, 0, -9.8F, 0));
  const auto samples = read_samples(source, 1);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_GE(samples[0].stamp_s, before_s);
  EXPECT_LE(samples[0].stamp_s, cover::clock::system_s());
}

TEST(MavlinkImuSource, BadUrlsAndTakenPortsThrow) {
  EXPECT_THROW(MavlinkImuSource("sctp://127.0.0.1:1", MavlinkStamp::Autopilot),
               std::invalid_argument);
  const auto port = free_port_base(1);
  MavlinkImuSource first("udpin://127.0.0.1:" + std::to_string(port), MavlinkStamp::Autopilot);
  EXPECT_THROW(
      MavlinkImuSource("udpin://127.0.0.1:" + std::to_string(port), MavlinkStamp::Autopilot),
      std::runtime_error);
}

}  // namespace
