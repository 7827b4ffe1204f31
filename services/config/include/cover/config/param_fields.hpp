#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
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
//
// A field may be a number (bounds below), an Eigen fixed vector (bounds on each component),
// a bool, a string (any text, or one_of fixed words), an enum (one_of its values, written
// as their to_string words) or a struct with its own fields() (a sub-section, read from a
// YAML mapping; its keys are reported dotted, "intercept.velocity_nodes").
struct Field {
  Field(const char* unit_, const char* doc_) : unit(unit_), doc(doc_) {}

  // Bounds of a number (each component of a vector): (lower, ...] with above(), [lower, ...]
  // with at_least(), [..., upper] with at_most(), [..., upper) with below(). Every number
  // must be finite.
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
    upper_open = false;
    return *this;
  }
  Field& below(double value) {
    upper = value;
    upper_open = true;
    return *this;
  }
  // Appended to the bound's error in parentheses: "must be in [0, 20] (0 disables)".
  Field& hint(const char* text) {
    note = text;
    return *this;
  }
  // The key must be written (otherwise the default stands).
  Field& required() {
    is_required = true;
    return *this;
  }
  // A string field's value must be one of these words.
  Field& one_of(std::initializer_list<const char*> choices) {
    words.assign(choices.begin(), choices.end());
    return *this;
  }
  // An enum field's values (a braced list or an array such as kModes), written in YAML as
  // to_string(value), found by argument-dependent lookup.
  template <typename E, std::size_t N, typename = std::enable_if_t<std::is_enum_v<E>>>
  Field& one_of(const E (&values)[N]) {
    words.clear();
    codes.clear();
    for (const E value : values) {
      words.emplace_back(to_string(value));
      codes.push_back(static_cast<long long>(value));
    }
    return *this;
  }
  // A sub-section's keys that this instance of it does not have (a struct shared by two
  // sections, one without some keys): neither read (so written, they are unknown keys),
  // checked, listed nor documented.
  Field& without(std::initializer_list<const char*> keys) {
    omitted.assign(keys.begin(), keys.end());
    return *this;
  }

  bool admits(double value) const {
    if (!std::isfinite(value)) return false;
    if (lower_open ? !(value > lower) : !(value >= lower)) return false;
    return upper_open ? value < upper : value <= upper;
  }
  // "(0, 20]", "> 0", ">= 1", "<= 5", "< 1.5", "finite".
  std::string range() const {
    const bool has_lower = std::isfinite(lower);
    const bool has_upper = std::isfinite(upper);
    if (has_lower && has_upper) {
      return std::string(lower_open ? "(" : "[") + format_number(lower) + ", " +
             format_number(upper) + (upper_open ? ")" : "]");
    }
    if (has_lower) return std::string(lower_open ? "> " : ">= ") + format_number(lower);
    if (has_upper) return std::string(upper_open ? "< " : "<= ") + format_number(upper);
    return "finite";
  }
  // "must be in (0, 20]", "must be >= 1", "must be a finite number", then the hint.
  // A bound carries the field's unit ("must be in (0, 1000] Hz"): the number alone would
  // leave a reader guessing whether 0.1 meant seconds or milliseconds.
  std::string requirement() const {
    std::string text = "must be a finite number";
    if (std::isfinite(lower) && std::isfinite(upper)) {
      text = "must be in " + range();
    } else if (std::isfinite(lower) || std::isfinite(upper)) {
      text = "must be " + range();
    }
    if (unit[0] && text != "must be a finite number") text += std::string(" ") + unit;
    return note[0] ? text + " (" + note + ")" : text;
  }
  // "px4, ardupilot".
  std::string choices() const {
    std::string text;
    for (const std::string& word : words) text += (text.empty() ? "" : ", ") + word;
    return text;
  }
  // Index of `word` in the words, -1 when it is none of them.
  int word_index(const std::string& word) const {
    const auto found = std::find(words.begin(), words.end(), word);
    return found == words.end() ? -1 : static_cast<int>(found - words.begin());
  }
  bool omits(const std::string& key) const {
    return std::find(omitted.begin(), omitted.end(), key) != omitted.end();
  }

  const char* unit;
  const char* doc;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_open = false;
  bool upper_open = false;
  bool is_required = false;
  const char* note = "";
  std::vector<std::string> words;  // one_of: the allowed words
  std::vector<long long> codes;    // an enum's values, in the order of `words`
  std::vector<std::string> omitted;
};

namespace detail {

// A struct with its own fields(): a sub-section.
struct ProbeVisitor {
  template <typename T>
  void operator()(const char*, T&, const Field&) {}
};
template <typename T, typename = void>
struct HasFields : std::false_type {};
template <typename T>
struct HasFields<
    T, std::void_t<decltype(T::fields(std::declval<T&>(), std::declval<ProbeVisitor&>()))>>
    : std::true_type {};

template <typename T>
inline constexpr bool kIsNumber = std::is_arithmetic_v<T> && !std::is_same_v<T, bool>;

// Shortest text that reads back as the same double (format_number's 6 digits may not).
inline std::string exact_number(double value) {
  if (!std::isfinite(value)) return format_number(value);
  for (int digits = 6; digits < 17; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << value;
    if (std::stod(out.str()) == value) return out.str();
  }
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

template <typename E>
std::string enum_word(E value, const Field& field) {
  for (std::size_t i = 0; i < field.codes.size(); ++i) {
    if (field.codes[i] == static_cast<long long>(value)) return field.words[i];
  }
  return std::to_string(static_cast<long long>(value));
}

// The value as the shipped files write it (vectors as "1, 2, 3").
template <typename T>
std::string value_text(const T& value, const Field& field) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_enum_v<T>) {
    return enum_word(value, field);
  } else if constexpr (std::is_floating_point_v<T>) {
    return exact_number(value);
  } else if constexpr (IsEigenFixed<T>::value) {
    std::string text;
    for (int i = 0; i < T::RowsAtCompileTime; ++i) {
      text += (i ? ", " : "") + exact_number(value[i]);
    }
    return text;
  } else {
    std::ostringstream out;
    out << value;
    return out.str();
  }
}

// Calls `inner` for each field of a sub-section but those its Field leaves out.
template <typename Inner>
struct WithoutVisitor {
  Inner& inner;
  const Field& section;
  template <typename T>
  void operator()(const char* key, T& value, const Field& field) {
    if (!section.omits(key)) inner(key, value, field);
  }
};

template <typename T, typename Visitor>
void visit_fields(T& value, const Field& section, Visitor& visit) {
  WithoutVisitor<Visitor> filtered{visit, section};
  std::decay_t<T>::fields(value, filtered);
}

struct LoadVisitor {
  YamlReader& reader;
  template <typename T>
  void operator()(const char* key, T& value, const Field& field) {
    if (field.is_required && !reader.has(key)) {
      throw ConfigError(reader.context() + "." + key + ": missing required key" +
                        line_of(reader.node()));
    }
    if constexpr (HasFields<T>::value) {
      YamlReader section = reader.child(key);
      LoadVisitor visit{section};
      visit_fields(value, field, visit);
      section.reject_unknown_keys();
    } else if constexpr (std::is_enum_v<T>) {
      std::string word = enum_word(value, field);
      read_word(key, word, field);
      value = static_cast<T>(field.codes[static_cast<std::size_t>(field.word_index(word))]);
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (field.words.empty()) {
        reader.optional(key, value);
      } else {
        read_word(key, value, field);
      }
    } else {
      reader.optional(key, value);
    }
  }

  void read_word(const char* key, std::string& word, const Field& field) {
    if (field.words.empty()) throw std::logic_error(std::string(key) + ": one_of has no words");
    reader.optional(key, word);
    if (field.word_index(word) < 0) {
      const YAML::Node node = reader.node().IsMap() ? reader.node()[key] : YAML::Node();
      throw ConfigError(reader.context() + "." + key + ": '" + word + "' is not one of " +
                        field.choices() + (node ? line_of(node) : ""));
    }
  }
};

// Throws ConfigError("<where>: must be in ...") when one value (not a sub-section) is out of
// its field's bounds or words.
template <typename T>
void check_value(const T& value, const Field& field, const std::string& where) {
  if constexpr (kIsNumber<T>) {
    check(field.admits(static_cast<double>(value)), where, field.requirement());
  } else if constexpr (IsEigenFixed<T>::value) {
    for (int i = 0; i < T::RowsAtCompileTime; ++i) {
      check(field.admits(value[i]), where, "each " + field.requirement());
    }
  } else if constexpr (std::is_same_v<T, std::string>) {
    check(field.words.empty() || field.word_index(value) >= 0, where,
          "'" + value + "' is not one of " + field.choices());
  }
}

struct CheckVisitor {
  const std::string& context;
  template <typename T>
  void operator()(const char* key, const T& value, const Field& field) {
    const std::string where = context + "." + key;
    if constexpr (HasFields<T>::value) {
      CheckVisitor visit{where};
      visit_fields(value, field, visit);
    } else {
      check_value(value, field, where);
    }
  }
};

// (dotted key, value as text) of every field, sub-sections' fields included.
struct ValueVisitor {
  std::string prefix;
  std::vector<std::pair<std::string, std::string>> values;
  template <typename T>
  void operator()(const char* key, const T& value, const Field& field) {
    if constexpr (HasFields<T>::value) {
      ValueVisitor visit{prefix + key + ".", {}};
      visit_fields(value, field, visit);
      values.insert(values.end(), visit.values.begin(), visit.values.end());
    } else {
      values.emplace_back(prefix + key, value_text(value, field));
    }
  }
};

// A Markdown cell: a '|' in the text would end it.
inline std::string table_cell(const std::string& text) {
  std::string cell;
  for (const char c : text) cell += c == '|' ? std::string("\\|") : std::string(1, c);
  return cell;
}

template <typename T>
std::string valid_text(const Field& field) {
  if constexpr (std::is_same_v<T, bool>) {
    return "true, false";
  } else if constexpr (std::is_enum_v<T> || std::is_same_v<T, std::string>) {
    return field.words.empty() ? "text" : "one of " + field.choices();
  } else if constexpr (IsEigenFixed<T>::value) {
    return std::to_string(T::RowsAtCompileTime) + " numbers, each " + field.range();
  } else {
    return field.range();
  }
}

struct TableVisitor {
  std::string prefix;
  std::string text;
  template <typename T>
  void operator()(const char* key, const T& value, const Field& field) {
    if constexpr (HasFields<T>::value) {
      TableVisitor visit{prefix + key + ".", {}};
      visit_fields(value, field, visit);
      text += visit.text;
    } else {
      const std::string required = field.is_required ? " (required)" : "";
      text += "| `" + prefix + key + "` | " + table_cell(field.unit) + " | " +
              table_cell(value_text(value, field)) + " | " + table_cell(valid_text<T>(field)) +
              required + " | " + table_cell(field.doc) + " |\n";
    }
  }
};

}  // namespace detail

// Reads every listed field that `reader` has (the defaults stand for the others; a
// required() one must be there), sub-sections from their mappings, then rejects keys that
// are no field, at every level.
template <typename Params>
void load_fields(Params& params, YamlReader& reader) {
  detail::LoadVisitor visit{reader};
  Params::fields(params, visit);
  reader.reject_unknown_keys();
}

// Throws ConfigError("<context>.<key>: must be in ...") for the first field out of bounds
// (sub-sections' keys dotted: "<context>.intercept.velocity_nodes: ...").
template <typename Params>
void check_fields(const Params& params, const std::string& context) {
  detail::CheckVisitor visit{context};
  Params::fields(params, visit);
}

// (dotted key, value as text) of every field, in declaration order: equal lists, equal
// params.
template <typename Params>
std::vector<std::pair<std::string, std::string>> field_values(const Params& params) {
  detail::ValueVisitor visit;
  Params::fields(params, visit);
  return visit.values;
}

// Every field's dotted key, in declaration order.
template <typename Params>
std::vector<std::string> field_keys() {
  std::vector<std::string> keys;
  for (auto& entry : field_values(Params{})) keys.push_back(std::move(entry.first));
  return keys;
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
