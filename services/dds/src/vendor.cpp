#include "cover/dds/vendor.hpp"

#include <cstdlib>

#include "cover/dds/dds_error.hpp"

namespace cover::dds {

Vendor parse_vendor(std::string_view name) {
  if (name == "fastdds" || name == "fast") return Vendor::FastDds;
  if (name == "cyclone" || name == "cyclonedds") return Vendor::Cyclone;
  throw DdsError("unknown DDS vendor '" + std::string(name) + "' (expected fastdds or cyclone)");
}

const char* vendor_name(Vendor vendor) {
  return vendor == Vendor::FastDds ? "fastdds" : "cyclone";
}

Vendor vendor_from_environment(Vendor fallback) {
  const char* name = std::getenv("COVER_DDS");
  return (name && *name) ? parse_vendor(name) : fallback;
}

}  // namespace cover::dds
