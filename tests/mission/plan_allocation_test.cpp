// The control thread must not touch the heap, a replan's steps included: plans are made on
// the PlanWorker's thread, which may allocate. Eigen allocates with malloc directly, not
// operator new, so this test replaces malloc itself (operator new ends there too), counts
// only what the thread stepping the loop allocates, and lives in its own executable.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>

#include "cover/sim/closed_loop.hpp"
#include "cover/sim/world.hpp"
#include "cover/sim/world_uav_io.hpp"
#include "cover/uav/controller_config.hpp"
#include "cover/uav/uav_loop.hpp"

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
thread_local bool t_counting = false;  // set on the control thread around each step
std::atomic<long> g_counted_allocations{0};
}  // namespace

#if COVER_COUNT_MALLOC
// glibc's own entry points: a program may replace malloc, free, calloc and realloc together.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void __libc_free(void* pointer);

void* malloc(std::size_t size) {
  if (t_counting) g_counted_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  if (t_counting) g_counted_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
  if (t_counting) g_counted_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
void free(void* pointer) {
  __libc_free(pointer);
}
}
#endif

namespace {

TEST(PlanOffThread, TheControlThreadDoesNotAllocateThroughAReplan) {
  if (!COVER_COUNT_MALLOC) GTEST_SKIP() << "malloc belongs to the sanitizer";
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  const cover::sim::Scenario scenario =
      cover::sim::Scenario::load_file(cover::sim::scenario_path("scenario2"));
  cover::sim::World world(scenario.world);
  cover::uav::UavLoop loop(0, world.ugv_count(), config);
  ASSERT_TRUE(loop.give_task(scenario.task).accepted);
  cover::sim::WorldUavInputs inputs(world);
  cover::sim::PlantCommandOutput plant;
  int counted_steps = 0;
  int counted_plans = 0;
  long allocations = 0;
  // The first stage's steps warm up (first solves, first plan); every later step counts,
  // the transition's and the final stage's replans included.
  while (world.state().time_s < scenario.max_duration_s &&
         !cover::mission::is_terminal(loop.task_state())) {
    const bool count = world.state().time_s > 1.0;
    const long before = g_counted_allocations.load();
    t_counting = count;
    const auto& out = loop.step(world.state().time_s, inputs, plant);
    t_counting = false;
    if (count) {
      allocations += g_counted_allocations.load() - before;
      ++counted_steps;
      if (out.status.planned) ++counted_plans;
    }
    world.advance(plant.command(), 0.01);
  }
  EXPECT_GE(counted_plans, 2) << "the count must include replans";
  EXPECT_GT(counted_steps, 300);
  EXPECT_EQ(allocations, 0) << "over " << counted_steps << " control steps";
}

}  // namespace
