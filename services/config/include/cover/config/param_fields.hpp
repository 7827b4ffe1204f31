#pragma once

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "cover/config/format_number.hpp"
#include "cover/config/yaml_reader.hpp"

namespace cover::config {

// One declaration per parameter struct. A struct lists each field once, with its key, unit,
// meaning and bounds:
//
//   template <typename Self, typename Visitor>
//   static void fields(Self& self, Visitor& visit) {
//     visit("heartbeat_timeout_s", self.heartbeat_timeout_s,
//           Field("s", "an agent not heard for this long is not up").above(0.0));
//   }
//
// and loading (load_fields), per-field validation (check_fields), the shipped-file tests
// (field_keys, field_values) and documentation (field_table) all walk that list, so a
// field cannot be loaded but not checked, or shipped but not tested. Checks between fields
// stay in the struct's validate(), after check_fields.
struct Field {
  Field(const char* unit_, const char* doc_) : unit(unit_), doc(doc_) {}

  // Bounds of a number (each component of a vector): (lower, ...] with above(), [lower, ...]
  // with at_least(), [..., upper] with at_most(). Every number must be finite.
  Field& above(double value) {
    lower = value;
    lower_open = true;
    return *this;
  }
  Field& at_least(double value) {
    lower = value;
    lower_open = false;
    return *this;
  }
  Field& at_most(double value) {
    upper = value;
    return *this;
  }

  bool admits(double value) const {
    if (!std::isfinite(value)) return false;
    if (lower_open ? !(value > lower) : !(value >= lower)) return false;
    return value <= upper;
  }
  // "(0, 20]", "> 0", ">= 1", "<= 5", "finite".
  std::string range() const {
    const bool has_lower = std::isfinite(lower);
    const bool has_upper = std::isfinite(upper);
    if (has_lower && has_upper) {
      return std::string(lower_open ? "(" : "[") + format_number(lower) + ", " +
             format_number(upper) + "]";
    }
    if (has_lower) return std::string(lower_open ? "> " : ">= ") + format_number(lower);
    if (has_upper) return "<= " + format_number(upper);
    return "finite";
  }
  // "must be in (0, 20]", "must be >= 1", "must be a finite number".
  std::string requirement() const {
    if (std::isfinite(lower) && std::isfinite(upper)) return "must be in " + range();
    if (std::isfinite(lower) || std::isfinite(upper)) return "must be " + range();
    return "must be a finite number";
  }

  const char* unit;
  const char* doc;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_open = false;
};

namespace detail {

struct LoadVisitor {
  YamlReader& reader;
  template <typename T>
  void operator()(const char* key, T& value, const Field&) {
    reader.optional(key, value);
  }
};

struct CheckVisitor {
  const std::string& context;
  template <typename T>
  void operator()(const char* key, const T& value, const Field& field) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      check(field.admits(static_cast<double>(value)), context + "." + key, field.requirement());
    } else if constexpr (IsEigenFixed<T>::value) {
      for (int i = 0; i < T::RowsAtCompileTime; ++i) {
        check(field.admits(value[i]), context + "." + key, "each " + field.requirement());
      }
    }
  }
};

struct KeyVisitor {
  std::vector<std::string> keys;
  template <typename T>
  void operator()(const char* key, const T&, const Field&) {
    keys.emplace_back(key);
  }
};

struct ValueVisitor {
  std::vector<std::pair<std::string, std::string>> values;
  template <typename T>
  void operator()(const char* key, const T& value, const Field&) {
    std::ostringstream out;
    if constexpr (IsEigenFixed<T>::value) {
      for (int i = 0; i < T::RowsAtCompileTime; ++i) out << (i ? ", " : "") << value[i];
    } else {
      out << value;
    }
    values.emplace_back(key, out.str());
  }
};

struct TableVisitor {
  std::string text;
  template <typename T>
  void operator()(const char* key, const T& value, const Field& field) {
    ValueVisitor shown;
    shown(key, value, field);
    text += "| `" + std::string(key) + "` | " + field.unit + " | " + shown.values[0].second +
            " | " + field.range() + " | " + field.doc + " |\n";
  }
};

}  // namespace detail

// Reads every listed field that `reader` has (the defaults stand for the others), then
// rejects keys that are no field.
template <typename Params>
void load_fields(Params& params, YamlReader& reader) {
  detail::LoadVisitor visit{reader};
  Params::fields(params, visit);
  reader.reject_unknown_keys();
}

// Throws ConfigError("<context>.<key>: must be in ...") for the first field out of bounds.
template <typename Params>
void check_fields(const Params& params, const std::string& context) {
  detail::CheckVisitor visit{context};
  Params::fields(params, visit);
}

template <typename Params>
std::vector<std::string> field_keys() {
  Params params;
  detail::KeyVisitor visit;
  Params::fields(params, visit);
  return visit.keys;
}

// (key, value as text) of every field, in declaration order: equal lists, equal params.
template <typename Params>
std::vector<std::pair<std::string, std::string>> field_values(const Params& params) {
  detail::ValueVisitor visit;
  Params::fields(params, visit);
  return visit.values;
}

// A Markdown table of the fields: key, unit, default, valid values, meaning.
template <typename Params>
std::string field_table() {
  Params params;
  detail::TableVisitor visit;
  visit.text = "| key | unit | default | valid | meaning |\n| --- | --- | --- | --- | --- |\n";
  Params::fields(params, visit);
  return visit.text;
}

}  // namespace cover::config
