#include "cover/shm/futex.hpp"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <climits>
#include <ctime>

namespace cover::shm {

namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "the futex word is the sequence's low half, its first 4 bytes");
static_assert(sizeof(std::atomic<std::uint64_t>) == 8);

// The sequence's low 32 bits, where the futex word lives.
std::uint32_t* low_half(const std::atomic<std::uint64_t>& word) {
  return reinterpret_cast<std::uint32_t*>(const_cast<std::atomic<std::uint64_t>*>(&word));
}

}  // namespace

void wake_all(std::atomic<std::uint64_t>& word) {
  // FUTEX_WAKE without FUTEX_PRIVATE_FLAG: the waiters are in other processes.
  syscall(SYS_futex, low_half(word), FUTEX_WAKE, INT_MAX, nullptr, nullptr, 0);
}

void wait_while(const std::atomic<std::uint64_t>& word, std::uint64_t seen,
                std::chrono::nanoseconds timeout) {
  if (timeout.count() <= 0) return;
  timespec relative{};
  relative.tv_sec = static_cast<time_t>(timeout.count() / 1'000'000'000);
  relative.tv_nsec = static_cast<long>(timeout.count() % 1'000'000'000);
  // The kernel compares the word with `seen` and sleeps only if they are equal, atomically
  // with respect to FUTEX_WAKE: a write between the caller's look and this call is not lost.
  syscall(SYS_futex, low_half(word), FUTEX_WAIT, static_cast<std::uint32_t>(seen), &relative,
          nullptr, 0);
}

}  // namespace cover::shm
