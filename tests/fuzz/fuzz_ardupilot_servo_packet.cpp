// ArduPilot SITL's servo packet parser (cover_firmware_link), fed any datagram.
// Contract: no crash; a packet exactly when the size is 40 or 72 and the magic is the one
// of that size; its channel count matches the size and the channels past it are zero;
// encoding the packet gives back the datagram's bytes; every PWM maps to an output in
// [0, 1].
#include <cstdint>
#include <vector>

#include "cover/firmware_link/ardupilot_servo_packet.hpp"
#include "fuzz_input.hpp"

namespace fl = cover::firmware_link;
using cover::fuzz::require;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto parsed = fl::parse_ardupilot_servo_packet(data, size);
  const bool sized =
      size == fl::kArduPilotServoPacket16Bytes || size == fl::kArduPilotServoPacket32Bytes;
  if (!sized) {
    require(!parsed.packet && parsed.error == fl::ServoPacketError::WrongSize,
            "a datagram of another size is refused as such");
    return 0;
  }
  const std::uint16_t magic = static_cast<std::uint16_t>(data[0] | (data[1] << 8));
  const std::uint16_t expected = size == fl::kArduPilotServoPacket16Bytes
                                     ? fl::kArduPilotServoMagic16
                                     : fl::kArduPilotServoMagic32;
  require(parsed.packet.has_value() == (magic == expected), "a packet iff its magic fits");
  if (!parsed.packet) {
    require(parsed.error == fl::ServoPacketError::WrongMagic, "refused for its magic");
    return 0;
  }
  const auto& packet = *parsed.packet;
  require(packet.channels == (size == fl::kArduPilotServoPacket16Bytes ? 16 : 32),
          "channels match the size");
  for (std::size_t i = packet.channels; i < packet.pwm_us.size(); ++i) {
    require(packet.pwm_us[i] == 0, "channels past the packet's are zero");
  }
  require(fl::encode_ardupilot_servo_packet(packet) == std::vector<std::uint8_t>(data, data + size),
          "encoding gives back the datagram");
  for (std::uint16_t pwm : packet.pwm_us) {
    const double u = fl::ardupilot_pwm_to_output(pwm);
    require(u >= 0.0 && u <= 1.0, "output in [0, 1]");
  }
  return 0;
}
