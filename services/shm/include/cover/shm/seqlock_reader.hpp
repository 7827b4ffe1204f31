#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>

#include "cover/shm/futex.hpp"
#include "cover/shm/segment.hpp"

namespace cover::shm {

// Reads the T that a SeqlockWriter (usually in another process) publishes, without ever
// blocking it. The mapping is read-only.
//
// Seqlock, reader side: load the sequence with acquire (the payload loads cannot move
// above it), copy the payload, an acquire fence (the copy cannot move below the check),
// load the sequence again. Equal and even means no write overlapped the copy; otherwise
// retry. See SeqlockWriter for the writer's half.
//
// The reader stays on the segment it opened: if the writer exits (it unlinks the name)
// and a new one starts, open a new reader. writer_alive() tells when that is needed.
template <typename T>
class SeqlockReader {
  static_assert(std::is_trivially_copyable_v<T>,
                "a shared-memory payload is copied byte-wise: T must be trivially copyable");

 public:
  // read() gives up after this many copies that a write overlapped, or this many spins
  // waiting for a write in progress (a few hundred microseconds: a 64 KiB write takes a
  // few, so only a writer preempted mid-write or writing back to back exhausts them).
  static constexpr int kMaxCopies = 16;
  static constexpr int kMaxSpins = 1 << 14;

  // Waits up to `wait` for the segment to exist with a complete header, then checks its
  // magic, layout version and payload size (sizeof(T)); std::runtime_error otherwise.
  static SeqlockReader open(const std::string& name, std::uint32_t layout_version,
                            std::chrono::milliseconds wait) {
    return SeqlockReader(Segment::open(name, layout_version, sizeof(T), wait));
  }

  // Copies the latest complete value into `out` (and its stamp into `sim_time_ns`). False
  // when nothing was written yet, or when writes kept overlapping the copy (see
  // kMaxCopies): then `out` may hold a torn copy and must not be used.
  //
  // A writer that does nothing but write back to back starves readers (every copy
  // overlaps the next write): seqlocks suit a writer that works between writes.
  [[nodiscard]] bool read(T& out, std::int64_t* sim_time_ns = nullptr) {
    return copy_consistent(&out, 0, sizeof(T), sim_time_ns);
  }

  // As read(), but copies only the `Part` at byte `offset` of the T (offsetof a member):
  // a reader that needs one vehicle's slice of a fleet's world copies that slice, not the
  // whole world on every read (a UGV agent of a 32-UGV world: 4.6 KiB instead of ~190).
  template <typename Part>
  [[nodiscard]] bool read_part(std::size_t offset, Part& out, std::int64_t* sim_time_ns = nullptr) {
    static_assert(std::is_trivially_copyable_v<Part>, "a part is copied byte-wise");
    if (offset + sizeof(Part) > sizeof(T)) return false;
    return copy_consistent(&out, offset, sizeof(Part), sim_time_ns);
  }

  // The writer's sequence now: compare with last_read_sequence() to know whether anything
  // new was written without copying the payload. Odd while a write is in progress.
  std::uint64_t sequence() const {
    return segment_.header().sequence.load(std::memory_order_acquire);
  }
  // Blocks until the sequence is no longer `seen` (a write began or ended since), at most
  // `timeout`; may return early. For readers that would otherwise poll sequence().
  void wait_for_write(std::uint64_t seen, std::chrono::nanoseconds timeout) const {
    wait_while(segment_.header().sequence, seen, timeout);
  }
  // The sequence of the value the last successful read() returned (0 before any).
  std::uint64_t last_read_sequence() const { return last_read_sequence_; }

  std::int32_t writer_pid() const { return segment_.header().writer_pid; }
  bool writer_alive() const { return process_alive(writer_pid()); }
  const std::string& name() const { return segment_.name(); }

 private:
  // The seqlock's reader side over bytes [offset, offset + size) of the payload.
  bool copy_consistent(void* out, std::size_t offset, std::size_t size, std::int64_t* sim_time_ns) {
    const SegmentHeader& header = segment_.header();
    int copies = 0;
    int spins = 0;
    while (copies < kMaxCopies && spins < kMaxSpins) {
      const std::uint64_t before = header.sequence.load(std::memory_order_acquire);
      if (before == 0) return false;
      if (before % 2 == 1) {
        ++spins;
        cpu_relax();
        continue;
      }
      ++copies;
      std::memcpy(out, segment_.payload() + offset, size);
      const std::int64_t stamp = header.sim_time_ns.load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (header.sequence.load(std::memory_order_relaxed) == before) {
        if (sim_time_ns != nullptr) *sim_time_ns = stamp;
        last_read_sequence_ = before;
        return true;
      }
    }
    return false;
  }

  explicit SeqlockReader(Segment segment) : segment_(std::move(segment)) {}

  static void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }

  Segment segment_;
  std::uint64_t last_read_sequence_ = 0;
};

}  // namespace cover::shm
