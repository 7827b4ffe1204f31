// Planning a stage must not touch the heap once the planner's workspace and the result's
// trajectory are sized: count every malloc while it plans. Eigen allocates with malloc
// directly, not operator new, so this test replaces malloc itself (operator new ends there
// too) and lives in its own executable.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>

#include "cover/planner/benchmark_problems.hpp"
#include "cover/planner/stage_planner.hpp"

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
std::atomic<long> g_allocations{0};
}  // namespace

#if COVER_COUNT_MALLOC
// glibc's own entry points: a program may replace malloc, free, calloc and realloc together.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void __libc_free(void* pointer);

void* malloc(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
void free(void* pointer) {
  __libc_free(pointer);
}
}
#endif

namespace cover::planner {
namespace {

TEST(PlannerAllocation, PlanningIntoAResultDoesNotAllocate) {
  if (!COVER_COUNT_MALLOC) GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
  StagePlanner planner{PlannerParams{}};
  // Transition and final stages, starts above vmax, braking starts: the bench's mix.
  std::vector<StageProblem> problems = make_benchmark_problems(60);
  StageProblem at_goal = problems[0];
  at_goal.goal_position_m = at_goal.start_position_m;
  at_goal.start_velocity_m_s.setZero();
  at_goal.transition_stage = false;
  problems.push_back(at_goal);  // hold
  StageProblem bad = problems[1];
  bad.vmax_m_s = -1.0;
  problems.push_back(bad);  // invalid input: hold the start

  PlanResult result;
  planner.plan(problems[0], result);  // the result's trajectory gets its storage here
  ASSERT_TRUE(is_usable(result.status)) << result.reason;

  const long before = g_allocations.load();
  int usable = 0;
  for (const StageProblem& problem : problems) {
    planner.plan(problem, result);
    usable += is_usable(result.status) ? 1 : 0;
  }
  const long allocations = g_allocations.load() - before;
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(usable, static_cast<int>(problems.size()) - 1);  // all but the invalid one
  EXPECT_EQ(result.status, PlanStatus::InvalidInput);
}

// The counter does count: a plan into a fresh result allocates its trajectory.
TEST(PlannerAllocation, TheCounterSeesAFreshResultsTrajectory) {
  if (!COVER_COUNT_MALLOC) GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
  StagePlanner planner{PlannerParams{}};
  const std::vector<StageProblem> problems = make_benchmark_problems(1);
  const long before = g_allocations.load();
  const PlanResult result = planner.plan(problems[0]);
  EXPECT_GT(g_allocations.load() - before, 0);
  EXPECT_TRUE(is_usable(result.status));
}

}  // namespace
}  // namespace cover::planner
