#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace cover::mavlink {

// Wire constants of MAVLink v1 and v2 framing.
inline constexpr std::uint8_t kMagicV1 = 0xFE;
inline constexpr std::uint8_t kMagicV2 = 0xFD;
inline constexpr std::size_t kHeaderLengthV1 = 6;   // magic .. msgid (1 byte)
inline constexpr std::size_t kHeaderLengthV2 = 10;  // magic .. msgid (3 bytes)
inline constexpr std::size_t kChecksumLength = 2;
inline constexpr std::size_t kSignatureLength = 13;
inline constexpr std::size_t kMaxPayloadLength = 255;
inline constexpr std::size_t kMaxFrameLength =
    kHeaderLengthV2 + kMaxPayloadLength + kChecksumLength + kSignatureLength;
inline constexpr std::uint8_t kIncompatSigned = 0x01;

// One frame as it came off the wire, checksum verified. `payload` is zero-filled past
// `payload_length` up to kMaxPayloadLength, so a message decoder reads trimmed v2
// payloads (trailing zeros removed by the sender) and v1 ones alike.
struct Frame {
  std::uint8_t version = 2;  // 1 or 2
  std::uint8_t incompat_flags = 0;
  std::uint8_t compat_flags = 0;
  std::uint8_t seq = 0;
  std::uint8_t system_id = 0;
  std::uint8_t component_id = 0;
  std::uint32_t message_id = 0;
  std::uint8_t payload_length = 0;  // as on the wire (trimmed)
  std::array<std::uint8_t, kMaxPayloadLength> payload{};
  bool is_signed() const { return (incompat_flags & kIncompatSigned) != 0; }
  std::array<std::uint8_t, kSignatureLength> signature{};  // valid when is_signed()
};

// A frame to send, ready to write: `bytes[0, size)`.
struct EncodedFrame {
  std::array<std::uint8_t, kMaxFrameLength> bytes{};
  std::size_t size = 0;
};

}  // namespace cover::mavlink
