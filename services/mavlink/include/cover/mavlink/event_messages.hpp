#pragma once

#include <array>
#include <cstdint>

namespace cover::mavlink {

// The events protocol (common.xml, "Events Interface"): PX4 reports arming refusals, mode
// changes and failsafes as EVENTs, not STATUSTEXT. An event's `id` is the emitting
// component's namespace id in the top 8 bits and the 24 low bits of the FNV-1a hash of the
// event's name; its text and the types of its packed arguments live in the component's
// metadata (PX4: all_events.json). Not in node-mavlink 2.3.0's registry: the CRC_EXTRA
// values below were computed from common.xml's field lists with the MAVLink CRC rule, and
// the codec tests check them the same way.

struct Event {
  static constexpr std::uint32_t kId = 410;
  static constexpr std::uint8_t kCrcExtra = 160;
  static constexpr std::uint8_t kPayloadLength = 53;
  std::uint32_t id = 0;
  std::uint32_t event_time_boot_ms = 0;
  std::uint16_t sequence = 0;
  std::uint8_t destination_component = 0;
  std::uint8_t destination_system = 0;
  // 4 high bits: internal log level, 4 low bits: external (0 emergency .. 7 debug).
  std::uint8_t log_levels = 0;
  std::array<std::uint8_t, 40> arguments{};  // packed little-endian, as the metadata types
  void pack(std::uint8_t* payload) const;
  static Event unpack(const std::uint8_t* payload);
};

struct CurrentEventSequence {
  static constexpr std::uint32_t kId = 411;
  static constexpr std::uint8_t kCrcExtra = 106;
  static constexpr std::uint8_t kPayloadLength = 3;
  std::uint16_t sequence = 0;
  std::uint8_t flags = 0;  // 1: the sequence was reset (reboot)
  void pack(std::uint8_t* payload) const;
  static CurrentEventSequence unpack(const std::uint8_t* payload);
};

}  // namespace cover::mavlink
