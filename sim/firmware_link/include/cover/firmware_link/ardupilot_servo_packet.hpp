#pragma once
// ArduPilot SITL's JSON backend, firmware -> physics: one binary servo packet per frame
// (libraries/SITL/SIM_JSON.h; the reference client unpacks it as '<HHI16H'), little-endian:
//   uint16 magic; uint16 frame_rate; uint32 frame_count; uint16 pwm[16 or 32]
// magic 18458 with 16 channels (40 bytes), 29569 with 32 (SERVO_32_ENABLE, 72 bytes).
// These are bytes from outside the simulator: the parser takes any size and content.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace cover::firmware_link {

inline constexpr std::uint16_t kArduPilotServoMagic16 = 18458;
inline constexpr std::uint16_t kArduPilotServoMagic32 = 29569;
inline constexpr std::size_t kArduPilotServoPacket16Bytes = 40;
inline constexpr std::size_t kArduPilotServoPacket32Bytes = 72;

struct ArduPilotServoPacket {
  std::uint16_t frame_rate_hz = 0;         // SIM_RATE_HZ
  std::uint32_t frame_count = 0;           // +1 per frame; restarts at 0 with the firmware
  std::uint8_t channels = 16;              // 16 or 32
  std::array<std::uint16_t, 32> pwm_us{};  // channels past `channels` are 0
};

enum class ServoPacketError : std::uint8_t { WrongSize, WrongMagic };
const char* to_string(ServoPacketError error);

struct ServoPacketParse {
  std::optional<ArduPilotServoPacket> packet;
  ServoPacketError error = ServoPacketError::WrongSize;  // when there is no packet
};

// One UDP datagram: a packet when its size and magic agree (40 bytes and 18458, or 72 and
// 29569), else why not.
ServoPacketParse parse_ardupilot_servo_packet(const std::uint8_t* data, std::size_t size);

// The datagram ArduPilot would send (16 or 32 channels as `packet.channels` says): for
// tests and peers that play the firmware.
std::vector<std::uint8_t> encode_ardupilot_servo_packet(const ArduPilotServoPacket& packet);

// A motor's output as the plant takes it: (pwm - 1000) / 1000 in [0, 1] (MOT_PWM_MIN/MAX
// 1000/2000). The motor model applies ArduCopter's spin_min/spin_max/expo curve to it.
double ardupilot_pwm_to_output(std::uint16_t pwm_us);

}  // namespace cover::firmware_link
