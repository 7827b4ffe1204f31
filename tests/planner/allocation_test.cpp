// Planning a stage must not touch the heap once the planner's workspace and the result's
// trajectory are sized: count every malloc while it plans (cover/test/malloc_counter.hpp:
// Eigen's included; its own executable).
#include <gtest/gtest.h>

#include "cover/planner/benchmark_problems.hpp"
#include "cover/planner/stage_planner.hpp"
#include "cover/test/malloc_counter.hpp"

namespace cover::planner {
namespace {

using test::count_this_thread;
using test::counted_allocations;
using test::malloc_counted;

TEST(PlannerAllocation, PlanningIntoAResultDoesNotAllocate) {
  if (!malloc_counted()) GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
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

  const long before = counted_allocations();
  int usable = 0;
  count_this_thread(true);
  for (const StageProblem& problem : problems) {
    planner.plan(problem, result);
    usable += is_usable(result.status) ? 1 : 0;
  }
  count_this_thread(false);
  const long allocations = counted_allocations() - before;
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(usable, static_cast<int>(problems.size()) - 1);  // all but the invalid one
  EXPECT_EQ(result.status, PlanStatus::InvalidInput);
}

// The counter does count: a plan into a fresh result allocates its trajectory.
TEST(PlannerAllocation, TheCounterSeesAFreshResultsTrajectory) {
  if (!malloc_counted()) GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
  StagePlanner planner{PlannerParams{}};
  const std::vector<StageProblem> problems = make_benchmark_problems(1);
  const long before = counted_allocations();
  count_this_thread(true);
  const PlanResult result = planner.plan(problems[0]);
  count_this_thread(false);
  EXPECT_GT(counted_allocations() - before, 0);
  EXPECT_TRUE(is_usable(result.status));
}

}  // namespace
}  // namespace cover::planner
