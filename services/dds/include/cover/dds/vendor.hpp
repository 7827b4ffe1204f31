#pragma once

#include <string>
#include <string_view>

namespace cover::dds {

// The DDS implementation behind a participant. Both are built in; one is chosen at run
// time, and processes on different vendors talk to each other (XCDR1, @final types).
enum class Vendor { FastDds, Cyclone };

// "fastdds" | "cyclone" (also "fast", "cyclonedds"); throws DdsError otherwise.
Vendor parse_vendor(std::string_view name);
const char* vendor_name(Vendor vendor);

// The vendor named by $COVER_DDS, or `fallback` when it is unset.
Vendor vendor_from_environment(Vendor fallback = Vendor::FastDds);

}  // namespace cover::dds
