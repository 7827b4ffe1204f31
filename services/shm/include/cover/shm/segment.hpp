#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cover/shm/segment_header.hpp"

namespace cover::shm {

// One mapped POSIX shared-memory segment: a SegmentHeader followed by `payload_size`
// bytes. The untyped part of SeqlockWriter / SeqlockReader; use those.
class Segment {
 public:
  // Creates `name` read-write, fills and publishes the header with this process as
  // writer. An existing segment whose writer is dead, or whose header is garbage or never
  // completed, is logged and replaced. Throws std::runtime_error naming the segment and
  // the pid when a live process owns it, or naming the failing call.
  static Segment create(const std::string& name, std::uint32_t layout_version,
                        std::uint64_t payload_size);

  // Maps `name` read-only, waiting up to `wait` for another process to create it and
  // complete its header. Throws std::runtime_error when the deadline passes, or when the
  // magic, layout version or payload size differ from what the caller expects.
  static Segment open(const std::string& name, std::uint32_t layout_version,
                      std::uint64_t payload_size, std::chrono::milliseconds wait);

  // Unmaps; the creator also unlinks the name, if it still refers to this segment.
  ~Segment();
  Segment(Segment&& other) noexcept;
  Segment& operator=(Segment&& other) noexcept;
  Segment(const Segment&) = delete;
  Segment& operator=(const Segment&) = delete;

  const std::string& name() const { return name_; }
  const SegmentHeader& header() const { return *static_cast<const SegmentHeader*>(base_); }
  const std::byte* payload() const { return static_cast<const std::byte*>(base_) + kPayloadOffset; }
  // Writable views exist only in the creator's read-write mapping.
  SegmentHeader& writable_header();
  std::byte* writable_payload();

 private:
  Segment(std::string name, int fd, void* base, std::size_t size, bool owner);
  void release() noexcept;

  std::string name_;
  int fd_ = -1;
  void* base_ = nullptr;
  std::size_t size_ = 0;
  bool owner_ = false;
};

// Unlinks `name` whoever created it, for launchers and tests that clean up after a killed
// writer. Processes that have it mapped keep their mapping. False if it did not exist.
bool remove_segment(const std::string& name);

// True when process `pid` exists (kill(pid, 0) does not fail with ESRCH). A zombie, a
// child that exited but was not yet reaped, still exists.
bool process_alive(std::int32_t pid);

}  // namespace cover::shm
