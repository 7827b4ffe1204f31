// ArduPilotJsonLink against a peer that plays ArduPilot SITL over real UDP sockets: it sends
// servo packets from an ephemeral port as SITL does and reads the answers there.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cover/firmware_link/ardupilot_json_link.hpp"

namespace cover::firmware_link {
namespace {

using namespace std::chrono_literals;

// The firmware's side: an unbound-then-ephemeral UDP socket sending to the link's port.
class FirmwarePeer {
 public:
  explicit FirmwarePeer(int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    to_.sin_family = AF_INET;
    to_.sin_port = htons(static_cast<std::uint16_t>(port));
    to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  }
  ~FirmwarePeer() { ::close(fd_); }

  void send_frame(std::uint32_t frame_count, std::uint16_t pwm, std::uint8_t channels = 16) {
    ArduPilotServoPacket packet;
    packet.frame_rate_hz = 1000;
    packet.frame_count = frame_count;
    packet.channels = channels;
    for (int i = 0; i < channels; ++i) packet.pwm_us[i] = pwm;
    send_bytes(encode_ardupilot_servo_packet(packet));
  }
  void send_bytes(const std::vector<std::uint8_t>& bytes) {
    ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to_),
             sizeof(to_));
  }
  // The next answer within `timeout`.
  std::optional<std::string> answer(std::chrono::milliseconds timeout) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return std::nullopt;
    char buffer[2048];
    const ssize_t n = ::recv(fd_, buffer, sizeof(buffer), 0);
    if (n <= 0) return std::nullopt;
    return std::string(buffer, static_cast<std::size_t>(n));
  }

 private:
  int fd_;
  sockaddr_in to_{};
};

// A free UDP port above the firmware's range (9002 + 10 u), so tests run beside a real SITL.
int free_port() {
  std::mt19937 rng(static_cast<unsigned>(::getpid()));
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int port = std::uniform_int_distribution<int>(33000, 34000)(rng);
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const bool ok = ::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) == 0;
    ::close(fd);
    if (ok) return port;
  }
  return 0;
}

PlantSample sample_at(std::uint64_t step) {
  PlantSample sample;
  sample.firmware_step = step;
  sample.dt_s = 0.001;
  sample.firmware_time_s = static_cast<double>(step) * sample.dt_s;
  sim::UavImuSample imu;
  imu.specific_force_flu_m_s2 = {0.0, 0.0, 9.81};
  sample.sensors.imu = imu;
  return sample;
}

class ArduPilotJsonLinkTest : public ::testing::Test {
 protected:
  ArduPilotJsonLinkOptions options() {
    ArduPilotJsonLinkOptions o;
    o.port = port_;
    o.lockstep_timeout = 300ms;
    o.repeat_grace = 50ms;
    return o;
  }
  int port_ = free_port();
};

TEST_F(ArduPilotJsonLinkTest, LockstepOneAnswerPerFrame) {
  ArduPilotJsonLink link(options());
  FirmwarePeer firmware(port_);
  EXPECT_FALSE(link.wait_for_firmware(20ms));
  firmware.send_frame(0, 1000);
  ASSERT_TRUE(link.wait_for_firmware(1000ms));
  for (std::uint32_t frame = 1; frame <= 5; ++frame) {
    firmware.send_frame(frame, static_cast<std::uint16_t>(1000 + 100 * frame));
    const auto outputs = link.exchange(sample_at(frame));
    for (double u : outputs) EXPECT_NEAR(u, 0.1 * frame, 1e-12);
    const auto answer = firmware.answer(100ms);
    ASSERT_TRUE(answer);
    char expected[64];
    std::snprintf(expected, sizeof(expected), "\"timestamp\":%.17g,", 0.001 * frame);
    EXPECT_NE(answer->find(expected), std::string::npos) << *answer;
  }
  EXPECT_FALSE(firmware.answer(20ms)) << "one answer per frame";
  const auto stats = link.stats();
  EXPECT_EQ(stats.frames_sent, 5u);
  EXPECT_EQ(stats.answers, 6u);
  EXPECT_EQ(stats.answers_missed, 0u);
  EXPECT_TRUE(stats.armed);
  EXPECT_EQ(link.ardupilot_stats().last_frame_count, 5u);
  EXPECT_EQ(link.ardupilot_stats().frame_rate_hz, 1000);
}

TEST_F(ArduPilotJsonLinkTest, ARepeatedFrameIsAnsweredAgainWithoutAStep) {
  ArduPilotJsonLink link(options());
  FirmwarePeer firmware(port_);
  firmware.send_frame(0, 1000);
  ASSERT_TRUE(link.wait_for_firmware(1000ms));
  firmware.send_frame(1, 1200);
  link.exchange(sample_at(1));
  ASSERT_TRUE(firmware.answer(100ms));
  // The answer to frame 1 "was lost": the firmware sends frame 1 again, and nothing newer.
  firmware.send_frame(1, 1200);
  const auto outputs = link.exchange(sample_at(2));
  const auto first = firmware.answer(100ms);
  const auto again = firmware.answer(100ms);
  ASSERT_TRUE(first && again);
  EXPECT_NE(first->find("\"timestamp\":0.002"), std::string::npos);
  EXPECT_EQ(*again, *first) << "the repeat gets the same state, no new step";
  EXPECT_EQ(link.ardupilot_stats().repeats_answered, 1u);
  EXPECT_EQ(link.stats().answers_missed, 1u);  // frame 2 never came within the timeout
  EXPECT_NEAR(outputs[0], 0.2, 1e-12);
}

TEST_F(ArduPilotJsonLinkTest, RepeatsQueuedBeforeTheAnswerAreOvertaken) {
  ArduPilotJsonLink link(options());
  FirmwarePeer firmware(port_);
  // A slow start: SITL re-sent frame 0 while the simulator was not answering yet.
  firmware.send_frame(0, 1000);
  firmware.send_frame(0, 1000);
  firmware.send_frame(0, 1000);
  ASSERT_TRUE(link.wait_for_firmware(1000ms));
  firmware.send_frame(1, 1500);
  const auto outputs = link.exchange(sample_at(1));
  EXPECT_NEAR(outputs[0], 0.5, 1e-12);
  ASSERT_TRUE(firmware.answer(100ms));
  EXPECT_FALSE(firmware.answer(20ms)) << "the stale repeats were not answered";
  EXPECT_EQ(link.ardupilot_stats().repeats_answered, 0u);
  EXPECT_EQ(link.ardupilot_stats().repeats_dropped, 1u);
}

TEST_F(ArduPilotJsonLinkTest, RestartSkipAndGarbageAreCountedNotFatal) {
  ArduPilotJsonLink link(options());
  FirmwarePeer firmware(port_);
  firmware.send_frame(10, 1000);
  ASSERT_TRUE(link.wait_for_firmware(1000ms));
  firmware.send_bytes({1, 2, 3});
  firmware.send_frame(13, 1100, 32);  // 32 channels; 11 and 12 never came
  link.exchange(sample_at(1));
  firmware.send_frame(0, 1000);  // the firmware restarted
  link.exchange(sample_at(2));
  const auto stats = link.ardupilot_stats();
  EXPECT_EQ(stats.frames_skipped, 2u);
  EXPECT_EQ(stats.restarts, 1u);
  EXPECT_EQ(stats.last_frame_count, 0u);
  EXPECT_EQ(link.stats().frames_rejected, 1u);
  EXPECT_FALSE(link.stats().armed);
}

TEST_F(ArduPilotJsonLinkTest, RealtimeHoldsTheOutputsAndAnswersOnlyWhatCame) {
  auto o = options();
  o.pacing = Pacing::Realtime;
  o.realtime_timeout = 2ms;
  ArduPilotJsonLink link(o);
  FirmwarePeer firmware(port_);
  firmware.send_frame(0, 1300);
  ASSERT_TRUE(link.wait_for_firmware(1000ms));
  // Frame 0 answered; no frame 1 within 2 ms: the outputs stay and nothing more is sent.
  for (int step = 1; step <= 3; ++step) {
    const auto outputs = link.exchange(sample_at(step));
    EXPECT_NEAR(outputs[2], 0.3, 1e-12);
  }
  const auto answer = firmware.answer(100ms);
  ASSERT_TRUE(answer);
  EXPECT_EQ(answer->find("no_time_sync"), std::string::npos);
  EXPECT_FALSE(firmware.answer(20ms));
  EXPECT_EQ(link.stats().frames_sent, 1u);
  EXPECT_EQ(link.stats().answers_missed, 3u);
}

TEST_F(ArduPilotJsonLinkTest, RealtimeAnswersARepeatBeforeItsWaitEnds) {
  auto o = options();
  o.pacing = Pacing::Realtime;
  o.realtime_timeout = 20ms;  // shorter than the repeat grace (50 ms)
  ArduPilotJsonLink link(o);
  FirmwarePeer firmware(port_);
  firmware.send_frame(0, 1000);
  ASSERT_TRUE(link.wait_for_firmware(1000ms));
  link.exchange(sample_at(1));
  ASSERT_TRUE(firmware.answer(100ms));
  firmware.send_frame(0, 1000);  // the answer "was lost"
  link.exchange(sample_at(2));
  const auto again = firmware.answer(100ms);
  ASSERT_TRUE(again);
  EXPECT_NE(again->find("\"timestamp\":0.001"), std::string::npos) << *again;
  EXPECT_EQ(link.ardupilot_stats().repeats_answered, 1u);
}

TEST_F(ArduPilotJsonLinkTest, APortInUseIsRefused) {
  ArduPilotJsonLink link(options());
  EXPECT_THROW(ArduPilotJsonLink second(options()), std::system_error);
  EXPECT_NE(link.describe().find(std::to_string(port_)), std::string::npos);
}

}  // namespace
}  // namespace cover::firmware_link
