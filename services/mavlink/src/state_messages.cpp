#include "cover/mavlink/state_messages.hpp"

#include "byte_cursor.hpp"

namespace cover::mavlink {

using detail::PayloadReader;
using detail::PayloadWriter;

void EstimatorStatus::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(time_usec);
  w.put(vel_ratio);
  w.put(pos_horiz_ratio);
  w.put(pos_vert_ratio);
  w.put(mag_ratio);
  w.put(hagl_ratio);
  w.put(tas_ratio);
  w.put(pos_horiz_accuracy);
  w.put(pos_vert_accuracy);
  w.put(flags);
}

EstimatorStatus EstimatorStatus::unpack(const std::uint8_t* payload) {
  EstimatorStatus m;
  PayloadReader r(payload);
  r.get(m.time_usec);
  r.get(m.vel_ratio);
  r.get(m.pos_horiz_ratio);
  r.get(m.pos_vert_ratio);
  r.get(m.mag_ratio);
  r.get(m.hagl_ratio);
  r.get(m.tas_ratio);
  r.get(m.pos_horiz_accuracy);
  r.get(m.pos_vert_accuracy);
  r.get(m.flags);
  return m;
}

void EkfStatusReport::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(velocity_variance);
  w.put(pos_horiz_variance);
  w.put(pos_vert_variance);
  w.put(compass_variance);
  w.put(terrain_alt_variance);
  w.put(flags);
  w.put(airspeed_variance);
}

EkfStatusReport EkfStatusReport::unpack(const std::uint8_t* payload) {
  EkfStatusReport m;
  PayloadReader r(payload);
  r.get(m.velocity_variance);
  r.get(m.pos_horiz_variance);
  r.get(m.pos_vert_variance);
  r.get(m.compass_variance);
  r.get(m.terrain_alt_variance);
  r.get(m.flags);
  r.get(m.airspeed_variance);
  return m;
}

void LocalPositionNed::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(time_boot_ms);
  w.put(x);
  w.put(y);
  w.put(z);
  w.put(vx);
  w.put(vy);
  w.put(vz);
}

LocalPositionNed LocalPositionNed::unpack(const std::uint8_t* payload) {
  LocalPositionNed m;
  PayloadReader r(payload);
  r.get(m.time_boot_ms);
  r.get(m.x);
  r.get(m.y);
  r.get(m.z);
  r.get(m.vx);
  r.get(m.vy);
  r.get(m.vz);
  return m;
}

}  // namespace cover::mavlink
