#include "cover/mavlink/event_messages.hpp"

#include "byte_cursor.hpp"

namespace cover::mavlink {

using detail::PayloadReader;
using detail::PayloadWriter;

void Event::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(id);
  w.put(event_time_boot_ms);
  w.put(sequence);
  w.put(destination_component);
  w.put(destination_system);
  w.put(log_levels);
  w.put(arguments);
}

Event Event::unpack(const std::uint8_t* payload) {
  Event m;
  PayloadReader r(payload);
  r.get(m.id);
  r.get(m.event_time_boot_ms);
  r.get(m.sequence);
  r.get(m.destination_component);
  r.get(m.destination_system);
  r.get(m.log_levels);
  r.get(m.arguments);
  return m;
}

void CurrentEventSequence::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(sequence);
  w.put(flags);
}

CurrentEventSequence CurrentEventSequence::unpack(const std::uint8_t* payload) {
  CurrentEventSequence m;
  PayloadReader r(payload);
  r.get(m.sequence);
  r.get(m.flags);
  return m;
}

}  // namespace cover::mavlink
