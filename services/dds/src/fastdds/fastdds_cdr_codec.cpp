// CdrCodec on Fast DDS's generated type support (TopicDataType::serialize / deserialize).
#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <cstring>
#include <exception>

#include "cover/dds/cdr_codec.hpp"
#include "fastdds_type_ops.hpp"

namespace cover::dds {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::SerializedPayload_t;

struct CdrCodec::Vendor {
  std::unique_ptr<fdds::TopicDataType> topic_type;
  void* sample = nullptr;
  void (*delete_sample)(void*) = nullptr;
  ~Vendor() {
    if (sample != nullptr) delete_sample(sample);
  }
};

CdrCodec::CdrCodec(const TypeSupport& type) : type_(type), vendor_(std::make_unique<Vendor>()) {
  vendor_->topic_type.reset(type.fastdds->new_topic_type());
  vendor_->sample = type.fastdds->new_vendor_sample();
  vendor_->delete_sample = type.fastdds->delete_vendor_sample;
}

CdrCodec::~CdrCodec() = default;

bool CdrCodec::serialize(const void* sample, std::vector<std::uint8_t>& out) const {
  std::lock_guard<std::mutex> lock(mutex_);
  out.clear();
  type_.fastdds->to_vendor(sample, vendor_->sample);
  const std::uint32_t bound = vendor_->topic_type->getSerializedSizeProvider(vendor_->sample)();
  SerializedPayload_t payload(bound);
  if (!vendor_->topic_type->serialize(vendor_->sample, &payload)) return false;
  out.assign(payload.data, payload.data + payload.length);
  return true;
}

bool CdrCodec::deserialize(const std::uint8_t* data, std::size_t size, void* sample) const {
  // Header + at least nothing; the header's first byte is 0 for plain CDR / XCDR1.
  if (size < 4 || data[0] != 0x00 || (data[1] != 0x00 && data[1] != 0x01)) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  std::memcpy(payload.data, data, size);
  payload.length = static_cast<std::uint32_t>(size);
  try {
    // Fast CDR throws NotEnoughMemoryException on a payload shorter than its fields.
    if (!vendor_->topic_type->deserialize(&payload, vendor_->sample)) return false;
  } catch (const std::exception&) {
    return false;
  }
  type_.fastdds->from_vendor(vendor_->sample, sample);
  return true;
}

}  // namespace cover::dds
