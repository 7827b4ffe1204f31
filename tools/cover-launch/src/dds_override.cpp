#include "cover/launch/dds_override.hpp"

#include <fnmatch.h>

#include <stdexcept>

namespace cover::launch {

bool is_vendor(const std::string& name) {
  return name == "fastdds" || name == "cyclone";
}

DdsOverride parse_dds_override(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw std::invalid_argument("--dds " + text + ": expected NAME=VENDOR, e.g. 'ugv*=cyclone'");
  }
  DdsOverride override_entry{text.substr(0, equals), text.substr(equals + 1)};
  if (!is_vendor(override_entry.vendor)) {
    throw std::invalid_argument("--dds " + text + ": unknown vendor '" + override_entry.vendor +
                                "' (valid: fastdds, cyclone)");
  }
  return override_entry;
}

void apply_dds_overrides(std::vector<ProcessSpec>& processes,
                         const std::vector<DdsOverride>& overrides) {
  for (const auto& entry : overrides) {
    bool matched = false;
    for (auto& process : processes) {
      if (fnmatch(entry.pattern.c_str(), process.name.c_str(), 0) == 0) {
        process.dds = entry.vendor;
        matched = true;
      }
    }
    if (!matched) {
      throw std::invalid_argument("--dds " + entry.pattern + "=" + entry.vendor +
                                  ": no process is named like '" + entry.pattern + "'");
    }
  }
}

}  // namespace cover::launch
