#include "cover/mavlink/hil_messages.hpp"

#include "byte_cursor.hpp"

namespace cover::mavlink {

using detail::PayloadReader;
using detail::PayloadWriter;

// The field lists once, for packing and unpacking alike: wire order (by type size, then
// declaration order; extensions last).
namespace {

template <typename Message, typename Cursor>
void hil_sensor_fields_of(Message& m, Cursor& c) {
  c(m.time_usec);
  c(m.xacc);
  c(m.yacc);
  c(m.zacc);
  c(m.xgyro);
  c(m.ygyro);
  c(m.zgyro);
  c(m.xmag);
  c(m.ymag);
  c(m.zmag);
  c(m.abs_pressure);
  c(m.diff_pressure);
  c(m.pressure_alt);
  c(m.temperature);
  c(m.fields_updated);
  c(m.id);
}

template <typename Message, typename Cursor>
void hil_actuator_controls_fields_of(Message& m, Cursor& c) {
  c(m.time_usec);
  c(m.flags);
  c(m.controls);
  c(m.mode);
}

template <typename Message, typename Cursor>
void hil_state_quaternion_fields_of(Message& m, Cursor& c) {
  c(m.time_usec);
  c(m.attitude_quaternion);
  c(m.rollspeed);
  c(m.pitchspeed);
  c(m.yawspeed);
  c(m.lat);
  c(m.lon);
  c(m.alt);
  c(m.vx);
  c(m.vy);
  c(m.vz);
  c(m.ind_airspeed);
  c(m.true_airspeed);
  c(m.xacc);
  c(m.yacc);
  c(m.zacc);
}

template <typename Message, typename Cursor>
void hil_gps_fields_of(Message& m, Cursor& c) {
  c(m.time_usec);
  c(m.lat);
  c(m.lon);
  c(m.alt);
  c(m.eph);
  c(m.epv);
  c(m.vel);
  c(m.vn);
  c(m.ve);
  c(m.vd);
  c(m.cog);
  c(m.fix_type);
  c(m.satellites_visible);
  c(m.id);
  c(m.yaw);
}

struct Put {
  PayloadWriter w;
  template <typename T>
  void operator()(const T& value) {
    w.put(value);
  }
};

struct Get {
  PayloadReader r;
  template <typename T>
  void operator()(T& value) {
    r.get(value);
  }
};

}  // namespace

void HilSensor::pack(std::uint8_t* payload) const {
  Put put{PayloadWriter(payload)};
  hil_sensor_fields_of(*this, put);
}

HilSensor HilSensor::unpack(const std::uint8_t* payload) {
  HilSensor m;
  Get get{PayloadReader(payload)};
  hil_sensor_fields_of(m, get);
  return m;
}

void HilActuatorControls::pack(std::uint8_t* payload) const {
  Put put{PayloadWriter(payload)};
  hil_actuator_controls_fields_of(*this, put);
}

HilActuatorControls HilActuatorControls::unpack(const std::uint8_t* payload) {
  HilActuatorControls m;
  Get get{PayloadReader(payload)};
  hil_actuator_controls_fields_of(m, get);
  return m;
}

void HilStateQuaternion::pack(std::uint8_t* payload) const {
  Put put{PayloadWriter(payload)};
  hil_state_quaternion_fields_of(*this, put);
}

HilStateQuaternion HilStateQuaternion::unpack(const std::uint8_t* payload) {
  HilStateQuaternion m;
  Get get{PayloadReader(payload)};
  hil_state_quaternion_fields_of(m, get);
  return m;
}

void HilGps::pack(std::uint8_t* payload) const {
  Put put{PayloadWriter(payload)};
  hil_gps_fields_of(*this, put);
}

HilGps HilGps::unpack(const std::uint8_t* payload) {
  HilGps m;
  Get get{PayloadReader(payload)};
  hil_gps_fields_of(m, get);
  return m;
}

}  // namespace cover::mavlink
