#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/mavlink/frame.hpp"

namespace cover::mavlink {

// The common.xml messages COVER's flight-controller link speaks, field for field (units
// and frames as MAVLink defines them: NED / FRD, SI unless the name says otherwise).
// Each struct knows its id, CRC_EXTRA and full payload length, packs itself into a
// payload buffer in wire order (fields sorted by size, extensions last, little endian)
// and unpacks from a frame's zero-filled payload. `decode<M>(frame)` is nullopt when the
// frame's id is not M's.

struct Heartbeat {
  static constexpr std::uint32_t kId = 0;
  static constexpr std::uint8_t kCrcExtra = 50;
  static constexpr std::uint8_t kPayloadLength = 9;
  std::uint32_t custom_mode = 0;
  std::uint8_t type = 0;           // MAV_TYPE (2: quadrotor, 6: GCS, 18: onboard controller)
  std::uint8_t autopilot = 0;      // MAV_AUTOPILOT (3: ArduPilot, 12: PX4, 8: invalid)
  std::uint8_t base_mode = 0;      // MAV_MODE_FLAG (128: armed, 1: custom mode enabled)
  std::uint8_t system_status = 0;  // MAV_STATE
  std::uint8_t mavlink_version = 3;
  void pack(std::uint8_t* payload) const;
  static Heartbeat unpack(const std::uint8_t* payload);
};

struct SysStatus {
  static constexpr std::uint32_t kId = 1;
  static constexpr std::uint8_t kCrcExtra = 124;
  static constexpr std::uint8_t kPayloadLength = 43;
  std::uint32_t onboard_control_sensors_present = 0;
  std::uint32_t onboard_control_sensors_enabled = 0;
  std::uint32_t onboard_control_sensors_health = 0;
  std::uint16_t load = 0;             // d%
  std::uint16_t voltage_battery = 0;  // mV, UINT16_MAX: unknown
  std::int16_t current_battery = -1;  // cA, -1: unknown
  std::uint16_t drop_rate_comm = 0;   // c%
  std::uint16_t errors_comm = 0;
  std::uint16_t errors_count1 = 0;
  std::uint16_t errors_count2 = 0;
  std::uint16_t errors_count3 = 0;
  std::uint16_t errors_count4 = 0;
  std::int8_t battery_remaining = -1;  // %, -1: unknown
  // extensions
  std::uint32_t onboard_control_sensors_present_extended = 0;
  std::uint32_t onboard_control_sensors_enabled_extended = 0;
  std::uint32_t onboard_control_sensors_health_extended = 0;
  void pack(std::uint8_t* payload) const;
  static SysStatus unpack(const std::uint8_t* payload);
};

struct ScaledImu {
  static constexpr std::uint32_t kId = 26;
  static constexpr std::uint8_t kCrcExtra = 170;
  static constexpr std::uint8_t kPayloadLength = 24;
  std::uint32_t time_boot_ms = 0;
  std::int16_t xacc = 0, yacc = 0, zacc = 0;     // mG (FRD)
  std::int16_t xgyro = 0, ygyro = 0, zgyro = 0;  // mrad/s (FRD)
  std::int16_t xmag = 0, ymag = 0, zmag = 0;     // mgauss
  // extensions
  std::int16_t temperature = 0;  // cdegC, 0: unknown
  void pack(std::uint8_t* payload) const;
  static ScaledImu unpack(const std::uint8_t* payload);
};

struct AttitudeQuaternion {
  static constexpr std::uint32_t kId = 31;
  static constexpr std::uint8_t kCrcExtra = 246;
  static constexpr std::uint8_t kPayloadLength = 48;
  std::uint32_t time_boot_ms = 0;
  float q1 = 1.0F, q2 = 0.0F, q3 = 0.0F, q4 = 0.0F;            // w, x, y, z: FRD body in NED
  float rollspeed = 0.0F, pitchspeed = 0.0F, yawspeed = 0.0F;  // rad/s, FRD
  // extensions
  std::array<float, 4> repr_offset_q{};
  void pack(std::uint8_t* payload) const;
  static AttitudeQuaternion unpack(const std::uint8_t* payload);
};

struct CommandLong {
  static constexpr std::uint32_t kId = 76;
  static constexpr std::uint8_t kCrcExtra = 152;
  static constexpr std::uint8_t kPayloadLength = 33;
  std::array<float, 7> param{};  // param1..param7
  std::uint16_t command = 0;     // MAV_CMD
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t confirmation = 0;  // 0 first send, +1 per retransmission
  void pack(std::uint8_t* payload) const;
  static CommandLong unpack(const std::uint8_t* payload);
};

struct CommandAck {
  static constexpr std::uint32_t kId = 77;
  static constexpr std::uint8_t kCrcExtra = 143;
  static constexpr std::uint8_t kPayloadLength = 10;
  std::uint16_t command = 0;
  std::uint8_t result = 0;  // MAV_RESULT
  // extensions
  std::uint8_t progress = 0;
  std::int32_t result_param2 = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  void pack(std::uint8_t* payload) const;
  static CommandAck unpack(const std::uint8_t* payload);
};

struct SetAttitudeTarget {
  static constexpr std::uint32_t kId = 82;
  static constexpr std::uint8_t kCrcExtra = 49;
  static constexpr std::uint8_t kPayloadLength = 51;
  std::uint32_t time_boot_ms = 0;
  std::array<float, 4> q{1.0F, 0.0F, 0.0F, 0.0F};  // w, x, y, z
  float body_roll_rate = 0.0F;                     // rad/s, FRD
  float body_pitch_rate = 0.0F;                    // rad/s, FRD
  float body_yaw_rate = 0.0F;                      // rad/s, FRD
  float thrust = 0.0F;                             // normalised collective thrust, 0..1
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t type_mask = 0;  // ATTITUDE_TARGET_TYPEMASK (128: ignore attitude)
  // extensions
  std::array<float, 3> thrust_body{};
  void pack(std::uint8_t* payload) const;
  static SetAttitudeTarget unpack(const std::uint8_t* payload);
};

struct AttitudeTarget {
  static constexpr std::uint32_t kId = 83;
  static constexpr std::uint8_t kCrcExtra = 22;
  static constexpr std::uint8_t kPayloadLength = 37;
  std::uint32_t time_boot_ms = 0;
  std::array<float, 4> q{1.0F, 0.0F, 0.0F, 0.0F};
  float body_roll_rate = 0.0F;
  float body_pitch_rate = 0.0F;
  float body_yaw_rate = 0.0F;
  float thrust = 0.0F;
  std::uint8_t type_mask = 0;
  void pack(std::uint8_t* payload) const;
  static AttitudeTarget unpack(const std::uint8_t* payload);
};

struct HighresImu {
  static constexpr std::uint32_t kId = 105;
  static constexpr std::uint8_t kCrcExtra = 93;
  static constexpr std::uint8_t kPayloadLength = 63;
  std::uint64_t time_usec = 0;
  float xacc = 0.0F, yacc = 0.0F, zacc = 0.0F;     // m/s^2 (FRD specific force)
  float xgyro = 0.0F, ygyro = 0.0F, zgyro = 0.0F;  // rad/s (FRD)
  float xmag = 0.0F, ymag = 0.0F, zmag = 0.0F;     // gauss
  float abs_pressure = 0.0F;                       // hPa
  float diff_pressure = 0.0F;                      // hPa
  float pressure_alt = 0.0F;                       // m
  float temperature = 0.0F;                        // degC
  std::uint16_t fields_updated = 0;                // HIGHRES_IMU_UPDATED_FLAGS
  // extensions
  std::uint8_t id = 0;
  void pack(std::uint8_t* payload) const;
  static HighresImu unpack(const std::uint8_t* payload);
};

struct Timesync {
  static constexpr std::uint32_t kId = 111;
  static constexpr std::uint8_t kCrcExtra = 34;
  static constexpr std::uint8_t kPayloadLength = 18;
  std::int64_t tc1 = 0;  // ns; 0: a request
  std::int64_t ts1 = 0;  // ns
  // extensions
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  void pack(std::uint8_t* payload) const;
  static Timesync unpack(const std::uint8_t* payload);
};

struct BatteryStatus {
  static constexpr std::uint32_t kId = 147;
  static constexpr std::uint8_t kCrcExtra = 154;
  static constexpr std::uint8_t kPayloadLength = 54;
  std::int32_t current_consumed = -1;        // mAh
  std::int32_t energy_consumed = -1;         // hJ
  std::int16_t temperature = INT16_MAX;      // cdegC
  std::array<std::uint16_t, 10> voltages{};  // mV per cell, UINT16_MAX: none
  std::int16_t current_battery = -1;         // cA
  std::uint8_t id = 0;
  std::uint8_t battery_function = 0;
  std::uint8_t type = 0;
  std::int8_t battery_remaining = -1;  // %
  // extensions
  std::int32_t time_remaining = 0;  // s
  std::uint8_t charge_state = 0;
  std::array<std::uint16_t, 4> voltages_ext{};
  std::uint8_t mode = 0;
  std::uint32_t fault_bitmask = 0;
  void pack(std::uint8_t* payload) const;
  static BatteryStatus unpack(const std::uint8_t* payload);
};

struct ExtendedSysState {
  static constexpr std::uint32_t kId = 245;
  static constexpr std::uint8_t kCrcExtra = 130;
  static constexpr std::uint8_t kPayloadLength = 2;
  std::uint8_t vtol_state = 0;
  std::uint8_t landed_state = 0;  // MAV_LANDED_STATE
  void pack(std::uint8_t* payload) const;
  static ExtendedSysState unpack(const std::uint8_t* payload);
};

struct StatusText {
  static constexpr std::uint32_t kId = 253;
  static constexpr std::uint8_t kCrcExtra = 83;
  static constexpr std::uint8_t kPayloadLength = 54;
  std::uint8_t severity = 6;    // MAV_SEVERITY (6: info)
  std::array<char, 50> text{};  // not NUL-terminated when all 50 are used
  // extensions
  std::uint16_t id = 0;
  std::uint8_t chunk_seq = 0;
  void pack(std::uint8_t* payload) const;
  static StatusText unpack(const std::uint8_t* payload);
  // The text as a string (up to the first NUL); sets it, cut at 50 bytes.
  std::string text_string() const;
  void set_text(const std::string& value);
};

// The message of `frame` as M, or nullopt when the frame carries another id.
template <typename M>
std::optional<M> decode(const Frame& frame) {
  if (frame.message_id != M::kId) return std::nullopt;
  return M::unpack(frame.payload.data());
}

}  // namespace cover::mavlink
