#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cover/mavlink/event_messages.hpp"

namespace cover::fc_bridge {

// A PX4 EVENT in words. PX4 reports arming refusals, failsafes and mode changes only
// through the events protocol, never STATUSTEXT: without this, "arm: refused (temporarily
// rejected)" is all an operator learns.
struct EventText {
  std::uint8_t level = 6;  // the external log level, as MAV_SEVERITY (0 emergency .. 7 debug)
  std::string text;
  bool known = false;        // the event is in COVER's table (else `text` names its id)
  bool for_operator = true;  // false: a protocol-level event (summaries, levels 8-9)
};

// PX4's event id of a name: its namespace component (px4: 1) in the top 8 bits, the low 24
// bits of the name's FNV-1a-32 hash (libevents).
constexpr std::uint32_t px4_event_id(const char* name) {
  std::uint32_t hash = 2166136261U;
  for (const char* c = name; *c != '\0'; ++c) {
    hash = (hash ^ static_cast<std::uint8_t>(*c)) * 16777619U;
  }
  return (1U << 24) | (hash & 0xFFFFFFU);
}

// The text of the events an operator of COVER meets (the commander's arming, mode, failsafe
// and landing events, its arming and health checks), with their arguments rendered;
// others are named by id.
EventText describe_px4_event(const mavlink::Event& event);

}  // namespace cover::fc_bridge
