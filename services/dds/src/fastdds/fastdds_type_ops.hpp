#pragma once

#include <fastdds/dds/topic/TopicDataType.hpp>

namespace cover::dds {

// Fast DDS operations on one message type; instances are generated from the IDL.
struct FastDdsTypeOps {
  eprosima::fastdds::dds::TopicDataType* (*new_topic_type)();
  void* (*new_vendor_sample)();
  void (*delete_vendor_sample)(void* sample);
  void (*to_vendor)(const void* neutral, void* vendor);
  void (*from_vendor)(const void* vendor, void* neutral);
};

}  // namespace cover::dds
