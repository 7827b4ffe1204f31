#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

namespace cover::shm {

// "COVERSHM" as the 8 bytes of a little-endian word, so a hex dump of the segment shows it.
inline constexpr std::uint64_t kSegmentMagic = 0x4d48535245564f43ull;

// The first 64 bytes of every segment; the payload (one trivially copyable T) follows.
//
// The writer fills every other field first and stores `magic` last with release
// semantics: a reader that loads the magic with acquire and finds it set sees a complete
// header. Atomics in memory shared between processes are well defined only when they
// are lock-free (then they are address-free), hence the static_asserts below.
struct alignas(64) SegmentHeader {
  std::atomic<std::uint64_t> magic;  // 0 while the writer is still filling the header
  std::uint32_t layout_version;      // chosen by the payload's owner, bumped on any change
  std::int32_t writer_pid;
  std::uint64_t payload_size;  // sizeof(T) of the writer
  // Seqlock: odd while a write is in progress, +2 per completed write, 0 = never written.
  std::atomic<std::uint64_t> sequence;
  std::atomic<std::int64_t> sim_time_ns;  // stamp of the payload, written inside the seqlock
};

static_assert(std::atomic<std::uint64_t>::is_always_lock_free,
              "shared-memory atomics must be lock-free to be address-free");
static_assert(std::atomic<std::int64_t>::is_always_lock_free,
              "shared-memory atomics must be lock-free to be address-free");
static_assert(sizeof(SegmentHeader) == 64, "the payload starts at byte 64");

// Where the payload starts; payload types may be aligned up to this.
inline constexpr std::size_t kPayloadOffset = sizeof(SegmentHeader);

}  // namespace cover::shm
