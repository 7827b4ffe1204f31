#include "cover/vocabulary/method.hpp"

namespace cover::sampc {

const char* to_string(Mode mode) {
  switch (mode) {
    case Mode::Cover:
      return "cover";
    case Mode::NoRefVxy:
      return "no-ref-vxy";
    case Mode::ConiMpc:
      return "coni-mpc";
    case Mode::Intercept:
      return "intercept";
  }
  return "unknown";
}

std::optional<Mode> parse_mode(std::string_view name) {
  for (const Mode mode : kModes) {
    if (name == to_string(mode)) return mode;
  }
  return std::nullopt;
}

std::string mode_names(std::string_view separator) {
  std::string text;
  for (const Mode mode : kModes) {
    if (!text.empty()) text += separator;
    text += to_string(mode);
  }
  return text;
}

}  // namespace cover::sampc
