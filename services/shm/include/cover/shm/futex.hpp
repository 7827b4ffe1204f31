#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

namespace cover::shm {

// Blocking on a word of a shared-memory segment, across processes (Linux futexes on the
// mapped page, not process-private ones): what lets a reader sleep until a writer's next
// write instead of polling. Futexes compare 32-bit words: these use the low half of the
// 64-bit sequence (its first 4 bytes on a little-endian machine), which changes on every
// write (+1, +2).
//
// Wakes every thread blocked in wait_while() on `word` (a syscall of about a microsecond,
// whether anybody waits or not).
void wake_all(std::atomic<std::uint64_t>& word);

// Blocks while `word`'s low half equals `seen`'s, for at most `timeout`. Returns at once
// when it differs already; may also return early (a signal, a spurious wake-up): callers
// look at the word again and decide.
void wait_while(const std::atomic<std::uint64_t>& word, std::uint64_t seen,
                std::chrono::nanoseconds timeout);

}  // namespace cover::shm
