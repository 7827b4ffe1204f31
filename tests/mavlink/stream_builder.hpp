#pragma once

#include <cstdint>
#include <vector>

#include "cover/mavlink/crc.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/frame.hpp"

// Builds byte streams for the parser tests: frames from an encoder, hand-made v1 frames
// and broken ones, appended to one buffer.
namespace cover::mavlink::test {

using Bytes = std::vector<std::uint8_t>;

inline Bytes bytes_of(const EncodedFrame& frame) {
  return Bytes(frame.bytes.begin(), frame.bytes.begin() + static_cast<long>(frame.size));
}

inline void append(Bytes& stream, const Bytes& more) {
  stream.insert(stream.end(), more.begin(), more.end());
}

template <typename M>
Bytes encode(Encoder& encoder, const M& message) {
  return bytes_of(encoder.encode(message));
}

// A MAVLink v1 frame (as an old radio sends it: the full non-extension payload).
template <typename M>
Bytes v1_frame(const M& message, std::uint8_t length, std::uint8_t seq, std::uint8_t system_id,
               std::uint8_t component_id) {
  std::uint8_t payload[kMaxPayloadLength] = {};
  message.pack(payload);
  Bytes frame{kMagicV1, length, seq, system_id, component_id, static_cast<std::uint8_t>(M::kId)};
  frame.insert(frame.end(), payload, payload + length);
  std::uint16_t crc = crc_accumulate(frame.data() + 1, frame.size() - 1, kCrcInit);
  crc = crc_accumulate(M::kCrcExtra, crc);
  frame.push_back(static_cast<std::uint8_t>(crc));
  frame.push_back(static_cast<std::uint8_t>(crc >> 8));
  return frame;
}

}  // namespace cover::mavlink::test
