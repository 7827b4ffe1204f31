#pragma once

#include <array>
#include <cstdint>

namespace cover::mavlink {

// The hardware-in-the-loop messages (common.xml) a simulator and PX4 SITL's
// simulator_mavlink exchange: the simulator sends the sensors (HIL_SENSOR, HIL_GPS) and the
// ground truth (HIL_STATE_QUATERNION); the firmware answers with its motor outputs
// (HIL_ACTUATOR_CONTROLS). NED world, FRD body, units as the field comments say.

// HIL_SENSOR.fields_updated: a sensor group is taken only when all of its bits are set.
namespace hil_sensor_fields {
inline constexpr std::uint32_t kAccel = 0b111;
inline constexpr std::uint32_t kGyro = 0b111000;
inline constexpr std::uint32_t kImu = kAccel | kGyro;  // 63
inline constexpr std::uint32_t kMag = 0b111000000;     // 448
inline constexpr std::uint32_t kDiffPressure = 1U << 10;
// abs_pressure (9), pressure_alt (11), temperature (12): 6656
inline constexpr std::uint32_t kBaro = (1U << 9) | (1U << 11) | (1U << 12);
}  // namespace hil_sensor_fields

struct HilSensor {
  static constexpr std::uint32_t kId = 107;
  static constexpr std::uint8_t kCrcExtra = 108;
  static constexpr std::uint8_t kPayloadLength = 65;
  std::uint64_t time_usec = 0;
  float xacc = 0.0F, yacc = 0.0F, zacc = 0.0F;     // m/s^2, specific force, FRD
  float xgyro = 0.0F, ygyro = 0.0F, zgyro = 0.0F;  // rad/s, FRD
  float xmag = 0.0F, ymag = 0.0F, zmag = 0.0F;     // gauss, FRD
  float abs_pressure = 0.0F;                       // hPa
  float diff_pressure = 0.0F;                      // hPa
  float pressure_alt = 0.0F;                       // m
  float temperature = 0.0F;                        // deg C
  std::uint32_t fields_updated = 0;                // hil_sensor_fields
  // extensions
  std::uint8_t id = 0;  // sensor instance; PX4: 0 is the primary IMU and drives lockstep
  void pack(std::uint8_t* payload) const;
  static HilSensor unpack(const std::uint8_t* payload);
};

// HIL_ACTUATOR_CONTROLS.flags
inline constexpr std::uint64_t kHilActuatorControlsLockstep = 1;

struct HilActuatorControls {
  static constexpr std::uint32_t kId = 93;
  static constexpr std::uint8_t kCrcExtra = 47;
  static constexpr std::uint8_t kPayloadLength = 81;
  std::uint64_t time_usec = 0;       // the firmware's (lockstep) time
  std::uint64_t flags = 0;           // on the wire before controls
  std::array<float, 16> controls{};  // PX4: motors 0..1, others -1..1; all 0 while disarmed
  std::uint8_t mode = 0;             // MAV_MODE_FLAG: 128 armed
  void pack(std::uint8_t* payload) const;
  static HilActuatorControls unpack(const std::uint8_t* payload);
};

struct HilStateQuaternion {
  static constexpr std::uint32_t kId = 115;
  static constexpr std::uint8_t kCrcExtra = 4;
  static constexpr std::uint8_t kPayloadLength = 64;
  std::uint64_t time_usec = 0;
  std::array<float, 4> attitude_quaternion{1.0F, 0.0F, 0.0F, 0.0F};  // w, x, y, z: FRD in NED
  float rollspeed = 0.0F, pitchspeed = 0.0F, yawspeed = 0.0F;        // rad/s, FRD
  std::int32_t lat = 0, lon = 0;                                     // degE7
  std::int32_t alt = 0;                                              // mm AMSL
  std::int16_t vx = 0, vy = 0, vz = 0;                               // cm/s, NED
  std::uint16_t ind_airspeed = 0, true_airspeed = 0;                 // cm/s
  std::int16_t xacc = 0, yacc = 0, zacc = 0;                         // mG, FRD
  void pack(std::uint8_t* payload) const;
  static HilStateQuaternion unpack(const std::uint8_t* payload);
};

struct HilGps {
  static constexpr std::uint32_t kId = 113;
  static constexpr std::uint8_t kCrcExtra = 124;
  static constexpr std::uint8_t kPayloadLength = 39;
  std::uint64_t time_usec = 0;
  std::int32_t lat = 0, lon = 0;        // degE7
  std::int32_t alt = 0;                 // mm AMSL
  std::uint16_t eph = UINT16_MAX;       // cm (HDOP x 100), UINT16_MAX: unknown
  std::uint16_t epv = UINT16_MAX;       // cm (VDOP x 100)
  std::uint16_t vel = UINT16_MAX;       // cm/s ground speed
  std::int16_t vn = 0, ve = 0, vd = 0;  // cm/s, NED
  std::uint16_t cog = UINT16_MAX;       // cdeg
  std::uint8_t fix_type = 0;            // 3: 3D fix
  std::uint8_t satellites_visible = 255;
  // extensions
  std::uint8_t id = 0;
  std::uint16_t yaw = 0;  // cdeg, 0: unknown
  void pack(std::uint8_t* payload) const;
  static HilGps unpack(const std::uint8_t* payload);
};

}  // namespace cover::mavlink
