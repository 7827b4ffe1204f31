#pragma once

#include <string>
#include <utility>

namespace cover::firmware {

// `NAME=VALUE` (a --param flag): NAME in A-Z0-9_ (up to 16, MAVLink's param_id), VALUE a
// number; throws config::ConfigError.
std::pair<std::string, std::string> parse_param_assignment(const std::string& text);

}  // namespace cover::firmware
