#pragma once

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "cover/dds/json_codec.hpp"
#include "cover/msg/types.hpp"

namespace cover::test {

// Fills every field of a message with a distinct, non-zero value derived from `counter`,
// so that a swapped, dropped or truncated field shows up in a comparison.
class SampleFiller {
 public:
  explicit SampleFiller(std::uint64_t seed) : counter_(seed) {}

  template <typename T>
  void fill(T& value) {
    ++counter_;
    if constexpr (std::is_same_v<T, bool>) {
      value = (counter_ % 2) == 1;
    } else if constexpr (std::is_enum_v<T>) {
      // Never 0 (the default), never out of range (Cyclone rejects an unknown value).
      constexpr std::uint32_t count = msg::EnumCount<T>::value;
      value = static_cast<T>(count > 1 ? 1 + counter_ % (count - 1) : 0);
    } else if constexpr (std::is_floating_point_v<T>) {
      value = static_cast<T>(counter_) + 0.125 + 1e-9 * static_cast<T>(counter_);
    } else if constexpr (std::is_integral_v<T>) {
      value = static_cast<T>(counter_ * 7919 % 100000 + 1);
    } else if constexpr (std::is_same_v<T, std::string>) {
      value = "s" + std::to_string(counter_) + "-Gk/\xc3\xbc";  // non-ASCII survives
    } else if constexpr (IsVector<T>::value) {
      value.resize(2 + counter_ % 3);
      for (auto& element : value) fill(element);
    } else {
      msg::visit_fields(value, [this](const char*, auto& field) { fill(field); });
    }
  }

 private:
  template <typename T>
  struct IsVector : std::false_type {};
  template <typename T>
  struct IsVector<std::vector<T>> : std::true_type {};
  std::uint64_t counter_;
};

// The JSON-pointer path of the first field that differs ("/processes/1/final_point_m/z"),
// or "" when the samples are equal. For messages; the generated operator== is the truth.
template <typename T>
std::string first_difference(const T& expected, const T& actual) {
  const auto patch =
      nlohmann::ordered_json::diff(cover::dds::to_json(expected), cover::dds::to_json(actual));
  return patch.empty() ? std::string() : patch[0]["path"].template get<std::string>();
}

}  // namespace cover::test
