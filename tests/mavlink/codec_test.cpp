#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"

namespace cover::mavlink {
namespace {

std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    bytes.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return bytes;
}

// ../shared/notes/mavlink.md: produced by node-mavlink 2.3.0.
const char* const kGoldenSetAttitudeTarget =
    "fd27000000ffbe520000e80300000000803f000000000000000000000000cdcccc3dcdcc4cbe9a99993e0000"
    "003f010180c0c7";

SetAttitudeTarget golden_setpoint() {
  SetAttitudeTarget m;
  m.time_boot_ms = 1000;
  m.q = {1.0F, 0.0F, 0.0F, 0.0F};
  m.body_roll_rate = 0.1F;
  m.body_pitch_rate = -0.2F;
  m.body_yaw_rate = 0.3F;
  m.thrust = 0.5F;
  m.target_system = 1;
  m.target_component = 1;
  m.type_mask = 128;
  return m;
}

TEST(MavlinkGolden, SetAttitudeTargetEncodesByteForByte) {
  Encoder encoder(255, 190);
  const EncodedFrame frame = encoder.encode(golden_setpoint());
  const std::vector<std::uint8_t> expected = from_hex(kGoldenSetAttitudeTarget);
  EXPECT_EQ(std::vector<std::uint8_t>(frame.bytes.begin(), frame.bytes.begin() + frame.size),
            expected);
}

TEST(MavlinkGolden, SetAttitudeTargetDecodes) {
  const std::vector<std::uint8_t> bytes = from_hex(kGoldenSetAttitudeTarget);
  StreamParser parser;
  std::vector<Frame> frames;
  parser.feed(bytes.data(), bytes.size(), [&](const Frame& f) { frames.push_back(f); });
  ASSERT_EQ(frames.size(), 1U);
  const auto m = decode<SetAttitudeTarget>(frames[0]);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->time_boot_ms, 1000U);
  EXPECT_EQ(m->body_pitch_rate, -0.2F);
  EXPECT_EQ(m->thrust, 0.5F);
  EXPECT_EQ(m->type_mask, 128);
  EXPECT_EQ(frames[0].system_id, 255);
  EXPECT_EQ(frames[0].component_id, 190);
  EXPECT_EQ(frames[0].payload_length, 39);
}

}  // namespace
}  // namespace cover::mavlink
