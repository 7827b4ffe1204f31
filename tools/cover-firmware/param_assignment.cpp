#include "param_assignment.hpp"

#include <cctype>
#include <cstdlib>

#include "cover/config/config_error.hpp"

namespace cover::firmware {
namespace {

bool valid_name(const std::string& name) {
  if (name.empty() || name.size() > 16) return false;  // MAVLink's param_id is 16 chars
  for (const char c : name) {
    if (!(std::isupper(static_cast<unsigned char>(c)) ||
          std::isdigit(static_cast<unsigned char>(c)) || c == '_')) {
      return false;
    }
  }
  return true;
}

bool valid_value(const std::string& value) {
  if (value.empty()) return false;
  char* end = nullptr;
  std::strtod(value.c_str(), &end);
  return end == value.c_str() + value.size();
}

}  // namespace

std::pair<std::string, std::string> parse_param_assignment(const std::string& text) {
  const auto equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const std::string value = equals == std::string::npos ? "" : text.substr(equals + 1);
  if (!valid_name(name) || !valid_value(value)) {
    throw config::ConfigError(
        "--param: expected NAME=VALUE (NAME in A-Z0-9_, VALUE a number), "
        "got '" +
        text + "'");
  }
  return {name, value};
}

}  // namespace cover::firmware
