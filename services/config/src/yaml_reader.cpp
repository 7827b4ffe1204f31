#include "cover/config/yaml_reader.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace cover::config {

std::string default_config_dir() {
  if (const char* dir = std::getenv("COVER_CONFIG_DIR")) return dir;
  return COVER_CONFIG_DIR;
}

namespace {

ConfigError syntax_error(const std::string& source, const YAML::Exception& e) {
  return ConfigError(source + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) +
                     ": " + e.msg);
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path) {
  // A directory opens as a stream on Linux, and reading it throws: say what it is instead
  // (an empty `task_file:` resolves to the folder it is relative to).
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw ConfigError(path + ": is a directory, not a YAML file");
  }
  std::ifstream stream(path);
  if (!stream) throw ConfigError(path + ": cannot open file");
  try {
    return YAML::Load(stream);
  } catch (const YAML::Exception& e) {
    throw syntax_error(path, e);
  } catch (const std::ios_base::failure& e) {
    throw ConfigError(path + ": cannot read file (" + e.what() + ")");
  }
}

YAML::Node parse_yaml(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw syntax_error(source, e);
  }
}

YamlReader::YamlReader(const YAML::Node& node, std::string context)
    : node_(node), context_(std::move(context)) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) {
    throw ConfigError(context_ + ": expected a mapping");
  }
}

std::string line_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? " (line " + std::to_string(mark.line + 1) + ")" : "";
}

YamlReader YamlReader::child(const std::string& key) {
  read_keys_.push_back(key);
  YAML::Node sub = node_.IsMap() ? node_[key] : YAML::Node();
  return YamlReader(sub ? sub : YAML::Node(YAML::NodeType::Map), context_ + "." + key);
}

bool YamlReader::has(const std::string& key) const {
  return node_.IsMap() && static_cast<bool>(node_[key]);
}

void YamlReader::reject_unknown_keys() const {
  if (!node_.IsMap()) return;
  for (const auto& entry : node_) {
    // A list or a mapping used as a key (`{[0, 0, 1]: x}`, often a stray comma) names nothing.
    if (!entry.first.IsScalar()) {
      throw ConfigError(context_ + ": a key that is not a name" + line_of(entry.first));
    }
    const auto key = entry.first.Scalar();
    if (std::find(read_keys_.begin(), read_keys_.end(), key) == read_keys_.end()) {
      throw ConfigError(context_ + ": unknown key '" + key + "'" + line_of(entry.first));
    }
  }
}

YamlReader open_section(const std::string& path, const std::string& section, bool required) {
  return open_section(load_yaml_file(path), path, section, required);
}

YamlReader open_section(const YAML::Node& document, const std::string& source,
                        const std::string& section, bool required) {
  YamlReader root(document, source);
  check(!required || root.has(section), source, "missing section '" + section + "'");
  YamlReader reader = root.child(section);
  root.reject_unknown_keys();
  return reader;
}

void check(bool condition, const std::string& context, const std::string& message) {
  if (!condition) throw ConfigError(context + ": " + message);
}

}  // namespace cover::config
