#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace cover::mavlink {

// The parameter protocol (common.xml): a companion asks for one parameter by name and the
// autopilot answers with its value. The 16-byte name is not NUL-terminated when all 16 are
// used. Values travel in a float field whatever their type (MAV_PARAM_TYPE), in one of two
// encodings (the autopilot's MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_*): PX4 copies an
// integer's bytes into the field ("bytewise": INT32 1 reads as the float 1.4e-45);
// ArduPilot converts it ("C cast": INT32 1 is 1.0F).
enum class ParamEncoding { Bytewise, CCast };

// The value of a PARAM_VALUE / PARAM_SET as a number, decoded by its type and encoding.
double param_value_of(float field, std::uint8_t param_type, ParamEncoding encoding);
// The float field that carries `value` of `param_type` in `encoding`.
float param_field_of(double value, std::uint8_t param_type, ParamEncoding encoding);

// A parameter's name as the wire carries it, and back.
std::array<char, 16> param_id_from(const std::string& name);
std::string param_id_string(const std::array<char, 16>& id);

struct ParamRequestRead {
  static constexpr std::uint32_t kId = 20;
  static constexpr std::uint8_t kCrcExtra = 214;
  static constexpr std::uint8_t kPayloadLength = 20;
  std::int16_t param_index = -1;  // -1: by name
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::array<char, 16> param_id{};
  void pack(std::uint8_t* payload) const;
  static ParamRequestRead unpack(const std::uint8_t* payload);
};

struct ParamValue {
  static constexpr std::uint32_t kId = 22;
  static constexpr std::uint8_t kCrcExtra = 220;
  static constexpr std::uint8_t kPayloadLength = 25;
  float param_value = 0.0F;
  std::uint16_t param_count = 0;
  std::uint16_t param_index = 0;
  std::array<char, 16> param_id{};
  std::uint8_t param_type = 9;  // MAV_PARAM_TYPE (9: REAL32, 6: INT32, 2: UINT8...)
  void pack(std::uint8_t* payload) const;
  static ParamValue unpack(const std::uint8_t* payload);
};

struct ParamSet {
  static constexpr std::uint32_t kId = 23;
  static constexpr std::uint8_t kCrcExtra = 168;
  static constexpr std::uint8_t kPayloadLength = 23;
  float param_value = 0.0F;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::array<char, 16> param_id{};
  std::uint8_t param_type = 9;
  void pack(std::uint8_t* payload) const;
  static ParamSet unpack(const std::uint8_t* payload);
};

}  // namespace cover::mavlink
