#pragma once
// Counts heap allocations for the "allocates nothing" tests. Eigen allocates with malloc
// directly, not operator new, so the executable that links cover_malloc_counter replaces
// malloc, calloc and realloc themselves (operator new ends there too); such a test lives in
// its own executable. Only the allocations of a thread that turned counting on are counted,
// and, apart, those of the threads the code under test starts (count_other_threads).

namespace cover::test {

// False where a sanitizer owns malloc (nothing is counted; the tests skip).
bool malloc_counted();

// Counting of the calling thread's allocations, off by default.
void count_this_thread(bool on);

// Allocations counted so far, every thread.
long counted_allocations();

// Counting of the allocations of every thread but the calling one (a worker the code under
// test runs), kept apart from counted_allocations(); off by default. The calling thread, and
// any thread that called count_this_thread(), is never counted here.
void count_other_threads(bool on);

// Allocations counted so far on other threads (count_other_threads).
long other_thread_allocations();

}  // namespace cover::test
