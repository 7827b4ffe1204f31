// ArduPilot's servo packet against bytes laid out by hand as the reference client reads
// them (struct '<HHI16H': magic, frame_rate, frame_count, pwm[16]; 32 channels: '<HHI32H').
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "cover/firmware_link/ardupilot_servo_packet.hpp"

namespace cover::firmware_link {
namespace {

void put16(std::vector<std::uint8_t>& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v & 0xFF));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}

std::vector<std::uint8_t> by_hand(std::uint16_t magic, int channels) {
  std::vector<std::uint8_t> b;
  put16(b, magic);
  put16(b, 1000);                                                        // frame_rate
  for (std::uint8_t byte : {0x78, 0x56, 0x34, 0x12}) b.push_back(byte);  // 0x12345678
  for (int i = 0; i < channels; ++i) put16(b, static_cast<std::uint16_t>(1000 + 10 * i));
  return b;
}

TEST(ArduPilotServoPacket, SixteenChannelsAsTheReferenceClientReadsThem) {
  const auto bytes = by_hand(18458, 16);
  ASSERT_EQ(bytes.size(), 40u);
  const auto parsed = parse_ardupilot_servo_packet(bytes.data(), bytes.size());
  ASSERT_TRUE(parsed.packet);
  EXPECT_EQ(parsed.packet->frame_rate_hz, 1000);
  EXPECT_EQ(parsed.packet->frame_count, 0x12345678u);
  EXPECT_EQ(parsed.packet->channels, 16);
  EXPECT_EQ(parsed.packet->pwm_us[0], 1000);
  EXPECT_EQ(parsed.packet->pwm_us[3], 1030);
  EXPECT_EQ(parsed.packet->pwm_us[15], 1150);
  EXPECT_EQ(parsed.packet->pwm_us[16], 0);
  EXPECT_EQ(encode_ardupilot_servo_packet(*parsed.packet), bytes);
}

TEST(ArduPilotServoPacket, ThirtyTwoChannels) {
  const auto bytes = by_hand(29569, 32);
  ASSERT_EQ(bytes.size(), 72u);
  const auto parsed = parse_ardupilot_servo_packet(bytes.data(), bytes.size());
  ASSERT_TRUE(parsed.packet);
  EXPECT_EQ(parsed.packet->channels, 32);
  EXPECT_EQ(parsed.packet->pwm_us[31], 1310);
  EXPECT_EQ(encode_ardupilot_servo_packet(*parsed.packet), bytes);
}

TEST(ArduPilotServoPacket, RefusesAWrongMagicOrSize) {
  // The 16-channel magic on a 72-byte packet, and the other way round.
  auto wide = by_hand(18458, 32);
  auto narrow = by_hand(29569, 16);
  EXPECT_EQ(parse_ardupilot_servo_packet(wide.data(), wide.size()).error,
            ServoPacketError::WrongMagic);
  EXPECT_FALSE(parse_ardupilot_servo_packet(narrow.data(), narrow.size()).packet);
  auto cut = by_hand(18458, 16);
  cut.pop_back();
  const auto parsed = parse_ardupilot_servo_packet(cut.data(), cut.size());
  EXPECT_FALSE(parsed.packet);
  EXPECT_EQ(parsed.error, ServoPacketError::WrongSize);
  EXPECT_FALSE(parse_ardupilot_servo_packet(nullptr, 0).packet);
}

TEST(ArduPilotServoPacket, PwmToOutputIsClipped) {
  EXPECT_DOUBLE_EQ(ardupilot_pwm_to_output(1000), 0.0);
  EXPECT_DOUBLE_EQ(ardupilot_pwm_to_output(1500), 0.5);
  EXPECT_DOUBLE_EQ(ardupilot_pwm_to_output(2000), 1.0);
  EXPECT_DOUBLE_EQ(ardupilot_pwm_to_output(0), 0.0);  // an unused output
  EXPECT_DOUBLE_EQ(ardupilot_pwm_to_output(2200), 1.0);
}

}  // namespace
}  // namespace cover::firmware_link
