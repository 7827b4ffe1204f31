#include "cover/firmware_link/ardupilot_servo_packet.hpp"

#include <algorithm>

namespace cover::firmware_link {
namespace {

std::uint16_t read_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}

std::uint32_t read_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

}  // namespace

const char* to_string(ServoPacketError error) {
  switch (error) {
    case ServoPacketError::WrongSize:
      return "neither 40 nor 72 bytes";
    case ServoPacketError::WrongMagic:
      return "magic does not match the size";
  }
  return "unknown";
}

ServoPacketParse parse_ardupilot_servo_packet(const std::uint8_t* data, std::size_t size) {
  ServoPacketParse result;
  std::uint16_t magic = 0;
  std::uint8_t channels = 0;
  if (size == kArduPilotServoPacket16Bytes) {
    magic = kArduPilotServoMagic16;
    channels = 16;
  } else if (size == kArduPilotServoPacket32Bytes) {
    magic = kArduPilotServoMagic32;
    channels = 32;
  } else {
    result.error = ServoPacketError::WrongSize;
    return result;
  }
  if (read_u16(data) != magic) {
    result.error = ServoPacketError::WrongMagic;
    return result;
  }
  ArduPilotServoPacket packet;
  packet.frame_rate_hz = read_u16(data + 2);
  packet.frame_count = read_u32(data + 4);
  packet.channels = channels;
  for (std::size_t i = 0; i < channels; ++i) packet.pwm_us[i] = read_u16(data + 8 + 2 * i);
  result.packet = packet;
  return result;
}

std::vector<std::uint8_t> encode_ardupilot_servo_packet(const ArduPilotServoPacket& packet) {
  const bool wide = packet.channels > 16;
  std::vector<std::uint8_t> out;
  out.reserve(wide ? kArduPilotServoPacket32Bytes : kArduPilotServoPacket16Bytes);
  put_u16(out, wide ? kArduPilotServoMagic32 : kArduPilotServoMagic16);
  put_u16(out, packet.frame_rate_hz);
  put_u16(out, static_cast<std::uint16_t>(packet.frame_count & 0xFFFF));
  put_u16(out, static_cast<std::uint16_t>(packet.frame_count >> 16));
  const std::size_t channels = wide ? 32 : 16;
  for (std::size_t i = 0; i < channels; ++i) put_u16(out, packet.pwm_us[i]);
  return out;
}

double ardupilot_pwm_to_output(std::uint16_t pwm_us) {
  return std::clamp((static_cast<double>(pwm_us) - 1000.0) / 1000.0, 0.0, 1.0);
}

}  // namespace cover::firmware_link
