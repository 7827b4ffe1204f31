#pragma once

#include <nlohmann/json.hpp>

#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "cover/msg/types.hpp"

namespace cover::dds {

// JSON <-> message conversion driven by the generated field visitors, so every IDL type
// gets it for free. Enums travel as their IDL names ("STAGE_FINAL").
class JsonError : public std::runtime_error {
 public:
  explicit JsonError(const std::string& what) : std::runtime_error(what) {}
};

namespace json_detail {

template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};

// Encoded objects keep the IDL field order (ordered_json), which reads better.
using Json = nlohmann::ordered_json;

template <typename T>
Json encode(const T& value);

template <typename J, typename T>
void decode(const J& json, T& value, const std::string& path);

template <typename T>
Json encode(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    return to_string(value);
  } else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {
    return value;
  } else if constexpr (IsVector<T>::value) {
    Json array = Json::array();
    for (const auto& element : value) array.push_back(encode(element));
    return array;
  } else {
    Json object = Json::object();
    msg::visit_fields(value,
                      [&](const char* name, const auto& field) { object[name] = encode(field); });
    return object;
  }
}

// Whether the JSON integer is a value of T: get<T>() would silently wrap one that is not.
template <typename T, typename J>
bool fits(const J& json) {
  using Max = unsigned long long;
  if (json.is_number_unsigned()) {
    return json.template get<Max>() <= static_cast<Max>(std::numeric_limits<T>::max());
  }
  const long long v = json.template get<long long>();
  if (v >= 0) return static_cast<Max>(v) <= static_cast<Max>(std::numeric_limits<T>::max());
  return std::is_signed_v<T> && v >= static_cast<long long>(std::numeric_limits<T>::min());
}

template <typename J, typename T>
void decode_struct(const J& json, T& value, const std::string& path) {
  if (!json.is_object()) throw JsonError(path + ": expected an object");
  std::vector<std::string> known;
  msg::visit_fields(value, [&](const char* name, auto& field) {
    known.emplace_back(name);
    if (const auto found = json.find(name); found != json.end()) {
      decode(*found, field, path.empty() ? name : path + "." + name);
    }
  });
  for (const auto& item : json.items()) {
    bool is_known = false;
    for (const auto& name : known) is_known = is_known || name == item.key();
    if (!is_known) {
      throw JsonError((path.empty() ? "" : path + ": ") + "no field '" + item.key() + "' in " +
                      (path.empty() ? std::string(T::kTypeName) : "this struct"));
    }
  }
}

template <typename J, typename T>
void decode(const J& json, T& value, const std::string& path) {
  if constexpr (std::is_enum_v<T>) {
    if (!json.is_string() || !from_string(json.template get<std::string>(), value)) {
      throw JsonError(path + ": expected an enum name, got " + json.dump());
    }
  } else if constexpr (std::is_same_v<T, bool>) {
    if (!json.is_boolean()) throw JsonError(path + ": expected true or false");
    value = json.template get<bool>();
  } else if constexpr (std::is_arithmetic_v<T>) {
    if (!json.is_number()) throw JsonError(path + ": expected a number, got " + json.dump());
    if constexpr (std::is_integral_v<T>) {
      if (!json.is_number_integer()) throw JsonError(path + ": expected an integer");
      if (!fits<T>(json)) {
        throw JsonError(path + ": " + json.dump() + " is out of range (" +
                        std::to_string(std::numeric_limits<T>::min()) + ".." +
                        std::to_string(std::numeric_limits<T>::max()) + ")");
      }
    }
    value = json.template get<T>();
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!json.is_string()) throw JsonError(path + ": expected a string");
    value = json.template get<std::string>();
  } else if constexpr (IsVector<T>::value) {
    if (!json.is_array()) throw JsonError(path + ": expected an array");
    value.resize(json.size());
    for (std::size_t i = 0; i < json.size(); ++i) {
      decode(json[i], value[i], path + "[" + std::to_string(i) + "]");
    }
  } else {
    decode_struct(json, value, path);
  }
}

}  // namespace json_detail

template <typename T>
json_detail::Json to_json(const T& sample) {
  return json_detail::encode(sample);
}

// Fields left out take their zero value; an unknown field or a wrong type throws JsonError
// naming the field path.
template <typename T, typename J>
T from_json(const J& json) {
  T sample{};
  json_detail::decode(json, sample, "");
  return sample;
}

}  // namespace cover::dds
