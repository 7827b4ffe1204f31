#include "cover/test/malloc_counter.hpp"

#include <atomic>
#include <cstddef>

#if defined(__SANITIZE_ADDRESS__)
#define COVER_COUNT_MALLOC 0  // the sanitizer owns malloc
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define COVER_COUNT_MALLOC 0
#endif
#endif
#ifndef COVER_COUNT_MALLOC
#define COVER_COUNT_MALLOC 1
#endif

namespace {
thread_local bool t_counting = false;
// The test's own threads: those that control counting, never "other" threads.
thread_local bool t_controls = false;
std::atomic<bool> g_count_others{false};
std::atomic<long> g_counted{0};
std::atomic<long> g_others{0};

void count() {
  if (t_counting) {
    g_counted.fetch_add(1, std::memory_order_relaxed);
  } else if (!t_controls && g_count_others.load(std::memory_order_relaxed)) {
    g_others.fetch_add(1, std::memory_order_relaxed);
  }
}
}  // namespace

namespace cover::test {

bool malloc_counted() {
  return COVER_COUNT_MALLOC != 0;
}
void count_this_thread(bool on) {
  t_controls = true;
  t_counting = on;
}
long counted_allocations() {
  return g_counted.load();
}
void count_other_threads(bool on) {
  t_controls = true;
  g_count_others.store(on);
}
long other_thread_allocations() {
  return g_others.load();
}

}  // namespace cover::test

#if COVER_COUNT_MALLOC
// glibc's own entry points: a program may replace malloc, free, calloc and realloc together.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void __libc_free(void* pointer);

void* malloc(std::size_t size) {
  count();
  return __libc_malloc(size);
}
void* calloc(std::size_t count_of, std::size_t size) {
  count();
  return __libc_calloc(count_of, size);
}
void* realloc(void* pointer, std::size_t size) {
  count();
  return __libc_realloc(pointer, size);
}
void free(void* pointer) {
  __libc_free(pointer);
}
}
#endif
