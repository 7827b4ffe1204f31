#pragma once

#include <yaml-cpp/yaml.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cover/config/param_fields.hpp"

namespace cover::config {

// "client_queue_kib" -> "--client-queue-kib": a setting's flag.
inline std::string flag_of_key(const std::string& key) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

// A process's settings: a YAML file's section (a struct with fields(), param_fields.hpp),
// then the flags given on the command line over some of its keys. Each setting is written
// once, in fields(): its flag, type and help come from there.
//
//   config::SettingsFlags<StationParams> settings("ground_station", dir + "/ground_station.yaml");
//   settings.add_to(app, {"port", "bind"});  // --config FILE, --port, --bind
//   ... app parsed ...
//   const StationParams p = settings.load();
//
// load() reads the file's section (an unknown key is an error naming it), puts each flag given
// over its key, then checks every bound once, after the flags: a file value a flag replaces is
// not checked, and an error names the flag and its key when the value came from one ("--port
// 70000 (ground_station.port): must be in [0, 65535]"), the file's key otherwise
// ("ground_station.port: ..."). Params::validate()
// runs last, for the checks between fields.
template <typename Params>
class SettingsFlags {
 public:
  SettingsFlags(std::string section, std::string default_file)
      : section_(std::move(section)), file_(std::move(default_file)) {}
  // Holds the texts the flags' callbacks write: not copied or moved once added to an app.
  SettingsFlags(const SettingsFlags&) = delete;
  SettingsFlags& operator=(const SettingsFlags&) = delete;

  // Adds --config and one flag per key (a number, bool, word or text field of the section's
  // top level; anything else is a std::logic_error, as is a key that is no field).
  void add_to(CLI::App& app, std::initializer_list<const char*> keys) {
    config_option_ =
        app.add_option("--config", file_,
                       "settings (" + section_ + ": section); the flags below override its keys")
            ->capture_default_str();
    Params params;
    AddVisitor visit{*this, app, {keys.begin(), keys.end()}};
    Params::fields(params, visit);
    if (!visit.keys.empty()) {
      throw std::logic_error(section_ + ": no field '" + visit.keys.front() + "' to give a flag");
    }
  }

  // The file's section, the flags given over it, every bound checked; throws ConfigError.
  Params load() const {
    YamlReader reader = open_section(load_yaml_file(file_), file_, section_, false);
    Params params;
    load_fields(params, reader);
    return over(std::move(params));
  }

  // The flags given over `params`, then every bound checked; throws ConfigError.
  Params over(Params params) const {
    ApplyVisitor apply{*this};
    Params::fields(params, apply);
    CheckVisitor check{*this};
    Params::fields(params, check);
    params.validate();
    return params;
  }

  const std::string& file() const { return file_; }
  // After parsing: `file` unless --config was given (a process whose --config-dir names the
  // folder of all its files).
  void default_to(std::string file) {
    if (config_option_ == nullptr || config_option_->count() == 0) file_ = std::move(file);
  }

  // "config/ground_station.yaml with --port 0 --bind 0.0.0.0": where the settings came from.
  std::string source() const {
    std::string text = file_;
    for (const auto& [key, value] : given_) {
      text += (text.size() == file_.size() ? " with " : " ") + flag_of_key(key) + " " + value;
    }
    return text;
  }

 private:
  template <typename T>
  static constexpr bool kFlaggable =
      std::is_arithmetic_v<T> || std::is_enum_v<T> || std::is_same_v<T, std::string>;

  template <typename T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, bool>) {
      return "BOOL";
    } else if constexpr (std::is_integral_v<T>) {
      return "INT";
    } else if constexpr (std::is_floating_point_v<T>) {
      return "FLOAT";
    } else {
      return "TEXT";
    }
  }

  static std::string help(const std::string& section, const char* key, const Field& field) {
    std::string text = field.doc;
    if (field.unit[0]) text += std::string(", ") + field.unit;
    if (!field.words.empty()) text += "; one of " + field.choices();
    return text + " (" + section + "." + key + ")";
  }

  struct AddVisitor {
    SettingsFlags& self;
    CLI::App& app;
    std::vector<std::string> keys;  // those not yet found
    template <typename T>
    void operator()(const char* key, T&, const Field& field) {
      const auto wanted = std::find(keys.begin(), keys.end(), key);
      if (wanted == keys.end()) return;
      keys.erase(wanted);
      if constexpr (!kFlaggable<T>) {
        throw std::logic_error(self.section_ + "." + key + ": a flag takes one value");
      } else {
        const std::string name = key;
        app.add_option_function<std::string>(
               flag_of_key(key),
               [this_ = &self, name](const std::string& text) { this_->given_[name] = text; },
               help(self.section_, key, field))
            ->type_name(type_name<T>());
      }
    }
  };

  struct ApplyVisitor {
    const SettingsFlags& self;
    template <typename T>
    void operator()(const char* key, T& value, const Field& field) {
      if constexpr (kFlaggable<T>) {
        const auto given = self.given_.find(key);
        if (given != self.given_.end())
          parse(self.where(key, given->second), given->second, value, field);
      }
    }
  };

  // `text` as the file's value would be read (YAML's numbers and booleans), a word of an
  // enum, or a string as written.
  template <typename T>
  static void parse(const std::string& where, const std::string& text, T& value,
                    const Field& field) {
    if constexpr (std::is_same_v<T, std::string>) {
      value = text;
    } else if constexpr (std::is_enum_v<T>) {
      const int index = field.word_index(text);
      check(index >= 0, where, "not one of " + field.choices());
      value = static_cast<T>(field.codes[static_cast<std::size_t>(index)]);
    } else {
      try {
        value = YAML::Node(text).as<T>();
      } catch (const YAML::Exception&) {
        const char* expected = std::is_same_v<T, bool> ? "true or false"
                               : std::is_integral_v<T> ? "a whole number"
                                                       : "a number";
        throw ConfigError(where + ": expected " + expected);
      }
    }
  }

  // "--port 70000 (ground_station.port)": a value a flag gave, in an error.
  std::string where(const std::string& key, const std::string& text) const {
    return flag_of_key(key) + " " + text + " (" + section_ + "." + key + ")";
  }

  struct CheckVisitor {
    const SettingsFlags& self;
    template <typename T>
    void operator()(const char* key, const T& value, const Field& field) {
      if constexpr (kFlaggable<T>) {
        const auto given = self.given_.find(key);
        if (given != self.given_.end()) {
          detail::check_value(value, field, self.where(key, given->second));
          return;
        }
      }
      detail::CheckVisitor visit{self.section_};
      visit(key, value, field);
    }
  };

  std::string section_;
  std::string file_;
  std::map<std::string, std::string> given_;  // key -> the flag's text
  CLI::Option* config_option_ = nullptr;      // --config, once added to an app
};

}  // namespace cover::config
