#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <new>
#include <string>
#include <type_traits>
#include <utility>

#include "cover/shm/futex.hpp"
#include "cover/shm/segment.hpp"

namespace cover::shm {

// The one writer of a shared-memory segment holding a T (one thread writes), published under a
// seqlock so that readers in other processes never see a half-written value and never block it.
//
// Seqlock, writer side: the sequence turns odd, a release fence keeps the payload stores
// from moving above that, the payload is written, and the even sequence is stored with
// release. A reader that saw any payload byte of this write therefore sees the odd (or a
// later) sequence when it checks again, and retries. The payload itself is copied with
// plain stores: formally a data race in the C++ model (the fences make it work on every
// compiler and CPU we target; std::atomic_ref would make it formal in C++20).
template <typename T>
class SeqlockWriter {
  static_assert(std::is_trivially_copyable_v<T>,
                "a shared-memory payload is copied byte-wise: T must be trivially copyable");
  static_assert(alignof(T) <= kPayloadOffset, "the payload is aligned to 64 bytes at most");

 public:
  // Creates `name` (see Segment::create: a stale segment is replaced, a live writer's
  // segment is an error naming its pid). `layout_version` identifies T's layout; bump it
  // whenever T changes so that old readers refuse the segment.
  SeqlockWriter(const std::string& name, std::uint32_t layout_version)
      : segment_(Segment::create(name, layout_version, sizeof(T))) {}

  // Publishes `value`, stamped with `sim_time_ns`.
  void write(const T& value, std::int64_t sim_time_ns) {
    update([&value](T& payload) { std::memcpy(&payload, &value, sizeof(T)); }, sim_time_ns);
  }

  // Lets `mutate(T&)` change the payload in place (e.g. append to a ring) without a copy
  // of the whole T. Readers retry until it returns. `mutate` must not throw: if it does,
  // the sequence stays odd and readers get no value until the next completed write.
  template <typename F>
  void update(F&& mutate, std::int64_t sim_time_ns) {
    SegmentHeader& header = segment_.writable_header();
    const std::uint64_t sequence = header.sequence.load(std::memory_order_relaxed);
    header.sequence.store(sequence + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    std::forward<F>(mutate)(payload());
    header.sim_time_ns.store(sim_time_ns, std::memory_order_relaxed);
    header.sequence.store(sequence + 2, std::memory_order_release);
    // Readers blocked in SeqlockReader::wait_for_write() (agents in lockstep) go on now.
    wake_all(header.sequence);
  }

  const std::string& name() const { return segment_.name(); }
  // 2 x the number of completed writes.
  std::uint64_t sequence() const {
    return segment_.header().sequence.load(std::memory_order_relaxed);
  }

 private:
  // T is trivially copyable and the memory was zero-filled: it is used as a T in place.
  T& payload() { return *std::launder(reinterpret_cast<T*>(segment_.writable_payload())); }

  Segment segment_;
};

}  // namespace cover::shm
