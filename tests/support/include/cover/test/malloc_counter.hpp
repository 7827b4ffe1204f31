#pragma once
// Counts heap allocations for the "allocates nothing" tests. Eigen allocates with malloc
// directly, not operator new, so the executable that links cover_malloc_counter replaces
// malloc, calloc and realloc themselves (operator new ends there too); such a test lives in
// its own executable. Only the allocations of a thread that turned counting on are counted.

namespace cover::test {

// False where a sanitizer owns malloc (nothing is counted; the tests skip).
bool malloc_counted();

// Counting of the calling thread's allocations, off by default.
void count_this_thread(bool on);

// Allocations counted so far, every thread.
long counted_allocations();

}  // namespace cover::test
