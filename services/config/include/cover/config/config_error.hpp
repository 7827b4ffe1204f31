#pragma once

#include <stdexcept>
#include <string>

namespace cover::config {

// Raised at load time (never inside a control loop) when a configuration file is
// missing, malformed, has an unknown key, or fails validation. The message names the
// file and the key path so the user can fix it without reading code.
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace cover::config
