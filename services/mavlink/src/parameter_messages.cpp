#include "cover/mavlink/parameter_messages.hpp"

#include <algorithm>

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
