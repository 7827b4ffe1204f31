#pragma once

#include <dds/dds.h>

#include <cstddef>

namespace cover::dds {

// Cyclone DDS operations on one message type; instances are generated from the IDL.
// `to_vendor` allocates strings and sequences with dds_alloc: free the vendor sample
// with dds_sample_free(sample, descriptor, DDS_FREE_CONTENTS).
struct CycloneTypeOps {
  const dds_topic_descriptor_t* descriptor;
  std::size_t vendor_sample_size;
  void (*to_vendor)(const void* neutral, void* vendor);
  void (*from_vendor)(const void* vendor, void* neutral);
};

}  // namespace cover::dds
