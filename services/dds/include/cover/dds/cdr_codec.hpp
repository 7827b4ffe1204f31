#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "cover/dds/type_support.hpp"

namespace cover::dds {

// A message type's serialized form as it crosses the wire: XCDR1 little endian with its
// 4-byte encapsulation header (00 01 00 00), made and read by the vendor's own generated
// type support (Fast DDS's; every COVER type is @final, whose XCDR1 bytes both vendors
// write alike). For the flight recorder (samples into MCAP) and the player (back out).
// Thread-safe; one codec per type is enough.
class CdrCodec {
 public:
  explicit CdrCodec(const TypeSupport& type);
  ~CdrCodec();
  CdrCodec(const CdrCodec&) = delete;
  CdrCodec& operator=(const CdrCodec&) = delete;

  // `sample` is a vendor-neutral cover::msg value of this codec's type. Replaces `out`;
  // false (out empty) when the vendor cannot serialize it.
  bool serialize(const void* sample, std::vector<std::uint8_t>& out) const;
  // Fills the vendor-neutral `sample`; false on bytes that are not this type's CDR
  // (truncated, wrong encapsulation...), never a crash.
  bool deserialize(const std::uint8_t* data, std::size_t size, void* sample) const;

  template <typename T>
  bool serialize(const T& sample, std::vector<std::uint8_t>& out) const {
    return serialize(static_cast<const void*>(&sample), out);
  }

 private:
  struct Vendor;
  const TypeSupport& type_;
  mutable std::mutex mutex_;
  std::unique_ptr<Vendor> vendor_;
};

}  // namespace cover::dds
