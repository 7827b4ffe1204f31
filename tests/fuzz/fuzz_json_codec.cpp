// The JSON codec of `cover pub` (services/dds json_codec.hpp), on every catalogued type
// (the first byte picks the topic). Contract: text that is JSON decodes or throws
// JsonError, never another exception; a decoded sample keeps every value it was given
// (no silent truncation of an out-of-range integer), and encode -> decode is the identity.
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "cover/dds/json_codec.hpp"
#include "cover/dds/topics.hpp"
#include "fuzz_input.hpp"

namespace {

using cover::fuzz::require;

// Every value of `given` is in `encoded` (which also has the fields left out).
void same_values(const nlohmann::json& given, const cover::dds::json_detail::Json& encoded,
                 const std::string& path) {
  if (given.is_object()) {
    for (const auto& item : given.items()) {
      require(encoded.contains(item.key()), path + "." + item.key() + " lost");
      same_values(item.value(), encoded.at(item.key()), path + "." + item.key());
    }
  } else if (given.is_array()) {
    require(encoded.is_array() && encoded.size() == given.size(), path + ": array size changed");
    for (std::size_t i = 0; i < given.size(); ++i) {
      same_values(given[i], encoded[i], path + "[" + std::to_string(i) + "]");
    }
  } else if (given.is_number_float()) {
    const double a = given.get<double>();
    const double b = encoded.get<double>();
    // A float field may hold a double given in JSON: allow its rounding.
    require(a == b || std::abs(a - b) <= 1e-6 * std::abs(a) ||
                (std::abs(a) < 1e-30 && std::abs(b) < 1e-30),
            path + ": " + given.dump() + " became " + encoded.dump());
  } else if (given.is_number_integer()) {
    // An integer given for a double field may round above 2^53; an integer field must hold it.
    if (encoded.is_number_float()) return;
    require(encoded.is_number_integer() && given.dump() == encoded.dump(),
            path + ": " + given.dump() + " became " + encoded.dump());
  } else {
    require(given.dump() == encoded.dump(),
            path + ": " + given.dump() + " became " + encoded.dump());
  }
}

template <typename T>
void check(const nlohmann::json& given) {
  T sample;
  try {
    sample = cover::dds::from_json<T>(given);
  } catch (const cover::dds::JsonError& e) {
    require(std::string(e.what()).size() > 0, "empty JsonError");
    return;
  } catch (const std::exception& e) {
    cover::fuzz::violated(std::string("not a JsonError: ") + e.what());
  }
  const auto encoded = cover::dds::to_json(sample);
  same_values(given, encoded, T::kTypeName);
  require(cover::dds::from_json<T>(encoded) == sample, "encode -> decode changed the sample");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cover::fuzz::FuzzInput in(data, size);
  const auto& catalog = cover::dds::topic_catalog();
  const auto& topic = catalog[in.byte() % catalog.size()];
  nlohmann::json given;
  try {
    given = nlohmann::json::parse(in.rest());
  } catch (const nlohmann::json::exception&) {
    return 0;  // cover pub: "invalid JSON: ..." (a syntax error, or a number beyond double)
  }
  const bool known = cover::msg::with_type(
      topic.type_name, [&](auto tag) { check<typename decltype(tag)::type>(given); });
  require(known, "catalogued type without type support: " + topic.type_name);
  return 0;
}
