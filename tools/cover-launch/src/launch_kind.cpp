#include "cover/launch/launch_kind.hpp"

namespace cover::launch {

const char* to_string(LaunchKind kind) {
  switch (kind) {
    case LaunchKind::Mission:
      return "mission";
    case LaunchKind::Standing:
      return "standing";
    case LaunchKind::Field:
      return "field";
  }
  return "mission";
}

std::optional<LaunchKind> parse_launch_kind(const std::string& text) {
  for (const LaunchKind kind : {LaunchKind::Mission, LaunchKind::Standing, LaunchKind::Field}) {
    if (text == to_string(kind)) return kind;
  }
  return std::nullopt;
}

}  // namespace cover::launch
