#pragma once

#include "cover/firmware/sitl_ports.hpp"

namespace cover::firmware {

// A SITL instance number N held on this host while the object lives, so that two tests (of
// one ctest run or of two) never start firmware with the same N, whose ports would collide.
// The claim is an abstract Unix socket named after N (as dds::DomainClaim): the kernel frees
// it when its holder exits or crashes, and nothing is left in the filesystem. A number whose
// ports another process holds now (a developer's own SITL, which claims nothing) is passed
// over.
class InstanceSlot {
 public:
  // The first free N of [first, last] for `firmware`; throws std::runtime_error naming why
  // when none is.
  static InstanceSlot claim(Autopilot firmware, int first, int last);

  InstanceSlot(InstanceSlot&& other) noexcept;
  InstanceSlot& operator=(InstanceSlot&& other) noexcept;
  InstanceSlot(const InstanceSlot&) = delete;
  InstanceSlot& operator=(const InstanceSlot&) = delete;
  ~InstanceSlot();

  int instance() const { return instance_; }

 private:
  InstanceSlot(int instance, int fd) : instance_(instance), fd_(fd) {}
  int instance_;
  int fd_;
};

// Whether this host lets us bind `use` now (it is free; released at once).
bool port_free(const PortUse& use);

}  // namespace cover::firmware
