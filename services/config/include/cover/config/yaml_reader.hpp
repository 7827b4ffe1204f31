#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <initializer_list>
#include <string>
#include <vector>

#include "cover/config/config_error.hpp"

namespace cover::config {

// Path of the repository's shipped configuration folder (set at build time).
std::string default_config_dir();

// Loads a YAML file; throws ConfigError naming the file on I/O or syntax errors.
YAML::Node load_yaml_file(const std::string& path);

// Parses YAML text held in memory (a file's content, a fuzzer's input); throws ConfigError
// naming `source` on syntax errors. Every loader's `from_yaml` takes what this returns.
YAML::Node parse_yaml(const std::string& text, const std::string& source);

// Reads the keys of one YAML mapping into parameter structs, the agilib way: every key
// is optional (the struct's default stands) unless read with `require`; a key of the
// wrong type, or a key the struct does not know, is an error that names the key path.
class YamlReader {
 public:
  // `context` is the human-readable location, e.g. "planner.yaml:planner".
  YamlReader(const YAML::Node& node, std::string context);

  template <typename T>
  void optional(const std::string& key, T& value);

  template <typename T>
  void require(const std::string& key, T& value);

  // Reads a sub-mapping; a missing key yields an empty mapping (defaults stand).
  YamlReader child(const std::string& key);

  // Throws when the mapping has keys that were never read: catches typos like `vmax_ms`.
  void reject_unknown_keys() const;

  bool has(const std::string& key) const;
  const std::string& context() const { return context_; }
  const YAML::Node& node() const { return node_; }

 private:
  template <typename T>
  void decode(const std::string& key, const YAML::Node& value_node, T& value) const;

  YAML::Node node_;
  std::string context_;
  std::vector<std::string> read_keys_;
};

// Opens a parameter file and returns a reader on its top-level `section` (e.g. "planner");
// any other top-level key is an error. A missing section is an error when `required`,
// otherwise the struct's defaults stand. Use in `Params::load_file`.
YamlReader open_section(const std::string& path, const std::string& section, bool required);

// The same on a document already parsed; `source` names it in errors. Use in
// `Params::from_yaml`.
YamlReader open_section(const YAML::Node& document, const std::string& source,
                        const std::string& section, bool required);

// " (line N)" of a node read from a file, "" when it has no position (built in code).
std::string line_of(const YAML::Node& node);

// Throws ConfigError("<context>: <message>") when `condition` is false. For `valid()`.
void check(bool condition, const std::string& context, const std::string& message);

// --- template implementation -------------------------------------------------------

namespace detail {
template <typename T>
struct IsEigenFixed : std::false_type {};
template <typename S, int R, int C, int O, int MR, int MC>
struct IsEigenFixed<Eigen::Matrix<S, R, C, O, MR, MC>> : std::bool_constant<(R > 0 && C == 1)> {};
}  // namespace detail

template <typename T>
void YamlReader::decode(const std::string& key, const YAML::Node& value_node, T& value) const {
  try {
    if constexpr (detail::IsEigenFixed<T>::value) {
      const auto list = value_node.as<std::vector<double>>();
      if (static_cast<int>(list.size()) != T::RowsAtCompileTime) {
        throw ConfigError(context_ + "." + key + ": expected " +
                          std::to_string(T::RowsAtCompileTime) + " numbers, got " +
                          std::to_string(list.size()) + line_of(value_node));
      }
      for (int i = 0; i < T::RowsAtCompileTime; ++i) value[i] = list[i];
    } else {
      value = value_node.as<T>();
    }
  } catch (const YAML::Exception& e) {
    throw ConfigError(context_ + "." + key + ": wrong type or value (" + e.msg + ")" +
                      line_of(value_node));
  }
}

template <typename T>
void YamlReader::optional(const std::string& key, T& value) {
  read_keys_.push_back(key);
  if (!node_.IsMap()) return;
  const YAML::Node value_node = node_[key];
  if (!value_node) return;
  decode(key, value_node, value);
}

template <typename T>
void YamlReader::require(const std::string& key, T& value) {
  read_keys_.push_back(key);
  const YAML::Node value_node = node_.IsMap() ? node_[key] : YAML::Node();
  if (!value_node) {
    throw ConfigError(context_ + ": missing required key '" + key + "'" + line_of(node_));
  }
  decode(key, value_node, value);
}

}  // namespace cover::config
