#include "cover/mavlink/parameter_messages.hpp"

#include <algorithm>
#include <cstring>

#include "byte_cursor.hpp"

namespace cover::mavlink {

using detail::PayloadReader;
using detail::PayloadWriter;

std::array<char, 16> param_id_from(const std::string& name) {
  std::array<char, 16> id{};
  std::copy_n(name.begin(), std::min(name.size(), id.size()), id.begin());
  return id;
}

std::string param_id_string(const std::array<char, 16>& id) {
  const auto end = std::find(id.begin(), id.end(), '\0');
  return std::string(id.begin(), end);
}

namespace {

// MAV_PARAM_TYPE: 1 UINT8, 2 INT8, 3 UINT16, 4 INT16, 5 UINT32, 6 INT32, 7 UINT64, 8 INT64,
// 9 REAL32, 10 REAL64.
double integer_from_bytes(std::uint32_t bits, std::uint8_t param_type) {
  switch (param_type) {
    case 1:
      return static_cast<std::uint8_t>(bits);
    case 2:
      return static_cast<std::int8_t>(bits);
    case 3:
      return static_cast<std::uint16_t>(bits);
    case 4:
      return static_cast<std::int16_t>(bits);
    case 5:
      return bits;
    default:
      return static_cast<std::int32_t>(bits);
  }
}

bool is_integer(std::uint8_t param_type) {
  return param_type >= 1 && param_type <= 8;
}

}  // namespace

double param_value_of(float field, std::uint8_t param_type, ParamEncoding encoding) {
  if (encoding == ParamEncoding::CCast || !is_integer(param_type)) return field;
  std::uint32_t bits = 0;
  std::memcpy(&bits, &field, sizeof bits);
  return integer_from_bytes(bits, param_type);
}

float param_field_of(double value, std::uint8_t param_type, ParamEncoding encoding) {
  if (encoding == ParamEncoding::CCast || !is_integer(param_type)) {
    return static_cast<float>(value);
  }
  const auto bits = static_cast<std::uint32_t>(static_cast<std::int64_t>(value));
  float field = 0.0F;
  std::memcpy(&field, &bits, sizeof field);
  return field;
}

void ParamRequestRead::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(param_index);
  w.put(target_system);
  w.put(target_component);
  w.put(param_id);
}

ParamRequestRead ParamRequestRead::unpack(const std::uint8_t* payload) {
  ParamRequestRead m;
  PayloadReader r(payload);
  r.get(m.param_index);
  r.get(m.target_system);
  r.get(m.target_component);
  r.get(m.param_id);
  return m;
}

void ParamValue::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(param_value);
  w.put(param_count);
  w.put(param_index);
  w.put(param_id);
  w.put(param_type);
}

ParamValue ParamValue::unpack(const std::uint8_t* payload) {
  ParamValue m;
  PayloadReader r(payload);
  r.get(m.param_value);
  r.get(m.param_count);
  r.get(m.param_index);
  r.get(m.param_id);
  r.get(m.param_type);
  return m;
}

void ParamSet::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(param_value);
  w.put(target_system);
  w.put(target_component);
  w.put(param_id);
  w.put(param_type);
}

ParamSet ParamSet::unpack(const std::uint8_t* payload) {
  ParamSet m;
  PayloadReader r(payload);
  r.get(m.param_value);
  r.get(m.target_system);
  r.get(m.target_component);
  r.get(m.param_id);
  r.get(m.param_type);
  return m;
}

}  // namespace cover::mavlink
