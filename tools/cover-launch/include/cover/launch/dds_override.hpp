#pragma once

#include <string>
#include <vector>

#include "cover/launch/launch_file.hpp"

namespace cover::launch {

// `--dds NAME=VENDOR`: NAME is a process name or an fnmatch glob such as `ugv*`.
struct DdsOverride {
  std::string pattern;
  std::string vendor;
};

// The vendors a child understands in COVER_DDS.
bool is_vendor(const std::string& name);

// Parses "NAME=VENDOR"; throws std::invalid_argument on a missing '=' or a bad vendor.
DdsOverride parse_dds_override(const std::string& text);

// Applies the overrides in order, so where globs overlap the later one wins. Throws
// std::invalid_argument when a pattern matches no process (a typo would otherwise pass).
void apply_dds_overrides(std::vector<ProcessSpec>& processes,
                         const std::vector<DdsOverride>& overrides);

}  // namespace cover::launch
