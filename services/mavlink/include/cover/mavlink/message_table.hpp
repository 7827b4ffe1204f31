#pragma once

#include <cstdint>
#include <optional>

namespace cover::mavlink {

// What the codec knows of a message id: its CRC_EXTRA (the seed that ties a frame to one
// message definition) and its full payload length (extensions included).
struct MessageInfo {
  std::uint32_t id = 0;
  std::uint8_t crc_extra = 0;
  std::uint8_t payload_length = 0;
  const char* name = "";
};

// The messages COVER's link speaks (common.xml); nullopt for any other id. A frame of an
// unknown id cannot have its checksum checked (no CRC_EXTRA) and is counted as unknown.
std::optional<MessageInfo> message_info(std::uint32_t message_id);

}  // namespace cover::mavlink
