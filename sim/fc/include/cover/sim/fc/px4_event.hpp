#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "cover/mavlink/event_messages.hpp"

namespace cover::sim::fc {

// PX4's event id of a name (libevents): its namespace component (px4: 1) in the top 8 bits,
// the low 24 bits of the name's FNV-1a-32 hash. The bridge decodes them with its own table
// (fc_bridge/core px4_events): the simulated PX4 writes them independently, so that a test
// meeting the two checks both.
constexpr std::uint32_t px4_event_id(const char* name) {
  std::uint32_t hash = 2166136261U;
  for (const char* c = name; *c != '\0'; ++c) {
    hash = (hash ^ static_cast<std::uint8_t>(*c)) * 16777619U;
  }
  return (1U << 24) | (hash & 0xFFFFFFU);
}

// The log levels of PX4's events (events::Log): the external one is what a ground station
// shows; PX4 logs each internally at Info.
enum class Px4EventLevel : std::uint8_t { Critical = 2, Warning = 4, Notice = 5, Info = 6 };

// One EVENT (410) as PX4 sends it: id, level, and its arguments packed little-endian in the
// order and types of PX4's metadata (all_events.json).
class Px4Event {
 public:
  Px4Event(const char* name, Px4EventLevel level) {
    message_.id = px4_event_id(name);
    message_.log_levels = static_cast<std::uint8_t>(
        (static_cast<std::uint8_t>(Px4EventLevel::Info) << 4) | static_cast<std::uint8_t>(level));
  }

  // Appends an argument (uint8_t, uint16_t, uint32_t, float ...); arguments past the
  // 40 bytes are dropped, as PX4 cannot send them either.
  template <typename T>
  Px4Event& arg(T value) {
    static_assert(std::is_arithmetic_v<T> && sizeof(T) <= 4);
    using Bits =
        std::conditional_t<sizeof(T) == 1, std::uint8_t,
                           std::conditional_t<sizeof(T) == 2, std::uint16_t, std::uint32_t>>;
    if (used_ + sizeof(T) > message_.arguments.size()) return *this;
    Bits bits = 0;
    std::memcpy(&bits, &value, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      message_.arguments[used_ + i] = static_cast<std::uint8_t>(bits >> (8 * i));
    }
    used_ += sizeof(T);
    return *this;
  }

  // The message, with its place in the autopilot's sequence of events and its time.
  mavlink::Event message(std::uint16_t sequence, std::uint32_t time_boot_ms) const {
    mavlink::Event e = message_;
    e.sequence = sequence;
    e.event_time_boot_ms = time_boot_ms;
    return e;
  }

 private:
  mavlink::Event message_;
  std::size_t used_ = 0;
};

// PX4's arm_disarm_reason_t values the simulated PX4 reports.
namespace px4_arm_reason {
inline constexpr std::uint8_t kExternalCommand = 4;
inline constexpr std::uint8_t kLanding = 6;
inline constexpr std::uint8_t kPreflightInaction = 7;
}  // namespace px4_arm_reason

// PX4's failsafe_action_t: Descend, the offboard-loss action without a position estimate.
inline constexpr std::uint8_t kPx4FailsafeDescend = 8;
// PX4's navigation_mode_t of OFFBOARD (events metadata), for a refused mode switch.
inline constexpr std::uint8_t kPx4NavigationOffboard = 7;

}  // namespace cover::sim::fc
