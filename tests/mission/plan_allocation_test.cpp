// No thread of the UAV loop touches the heap in steady flight, a replan and SAMPC's
// preparation after each command (the real-time-iteration split) included: the
// control thread never plans (the PlanWorker's thread does), and the worker plans into
// results sized once. Counts what the thread stepping the loop allocates and, apart, what
// every other thread (the worker) allocates (cover/test/malloc_counter.hpp: Eigen's
// included; its own executable).
#include <gtest/gtest.h>

#include <memory>

#include "cover/mission/plan_worker.hpp"
#include "cover/planner/benchmark_problems.hpp"
#include "cover/planner/stage_planner.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/sim/world.hpp"
#include "cover/sim/world_uav_io.hpp"
#include "cover/test/malloc_counter.hpp"
#include "cover/uav/controller_config.hpp"
#include "cover/uav/uav_loop.hpp"

namespace {

using cover::test::count_other_threads;
using cover::test::count_this_thread;
using cover::test::counted_allocations;
using cover::test::other_thread_allocations;

TEST(PlanOffThread, NoThreadAllocatesThroughASteadyReplan) {
  if (!cover::test::malloc_counted()) GTEST_SKIP() << "malloc belongs to the sanitizer";
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
  int sampc_steps = 0;
  int prepared_ahead = 0;  // steps whose SAMPC ran the feedback phase only
  bool counting_worker = false;
  const long worker_before = other_thread_allocations();
  // The first stage's steps warm up (first solves, first plan); every later step counts,
  // the transition's and the final stage's replans included. The worker counts from the
  // first such step at which it has no plan to make (it is idle then: lockstep).
  while (world.state().time_s < scenario.max_duration_s &&
         !cover::mission::is_terminal(loop.task_state())) {
    const bool count = world.state().time_s > 1.0;
    if (count && !counting_worker && !loop.controller()->plan_in_flight()) {
      count_other_threads(true);
      counting_worker = true;
    }
    const long before = counted_allocations();
    count_this_thread(count);
    const auto& out = loop.step(world.state().time_s, inputs, plant);
    count_this_thread(false);
    if (count) {
      allocations += counted_allocations() - before;
      ++counted_steps;
      if (out.status.planned && counting_worker) ++counted_plans;
      if (out.status.solve_us > 0.0) {
        ++sampc_steps;
        if (out.status.feedback_us < out.status.solve_us) ++prepared_ahead;
      }
    }
    world.advance(plant.command(), 0.01);
  }
  count_other_threads(false);
  EXPECT_GE(counted_plans, 2) << "the count must include replans";
  EXPECT_GT(counted_steps, 300);
  EXPECT_EQ(allocations, 0) << "control thread, over " << counted_steps << " steps";
  // The count covers the split loop: nearly every step prepared after the previous command
  // (the rest: a new stage's coast, an adopted plan, a frame switch prepare inline).
  EXPECT_GT(prepared_ahead, 0.95 * sampc_steps) << prepared_ahead << " of " << sampc_steps;
  EXPECT_EQ(other_thread_allocations() - worker_before, 0)
      << "worker thread, over " << counted_plans << " plans";
}

// The worker's count does see a worker that allocates: one that plans into a fresh result
// every time (as a PlanFunction returning StagePlanner::plan(problem) would).
TEST(PlanOffThread, TheCounterSeesAWorkerThatAllocates) {
  if (!cover::test::malloc_counted()) GTEST_SKIP() << "malloc belongs to the sanitizer";
  auto planner = std::make_shared<cover::planner::StagePlanner>(cover::planner::PlannerParams{});
  cover::mission::PlanWorker worker(
      [planner](const cover::planner::StageProblem& problem, cover::planner::PlanResult& result) {
        result = planner->plan(problem);
      },
      cover::planner::PlannerParams{}.pieces);
  const cover::planner::StageProblem problem = cover::planner::make_benchmark_problems(1)[0];
  cover::planner::PlanResult result;
  result.trajectory.reserve(cover::planner::PlannerParams{}.pieces);
  for (int warm = 0; warm < 3; ++warm)
    ASSERT_TRUE(worker.take(worker.request(problem), result, true));
  const long before = other_thread_allocations();
  count_other_threads(true);
  for (int plan = 0; plan < 3; ++plan)
    ASSERT_TRUE(worker.take(worker.request(problem), result, true));
  count_other_threads(false);
  EXPECT_GT(other_thread_allocations() - before, 0);
}

}  // namespace
