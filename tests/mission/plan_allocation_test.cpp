// The control thread must not touch the heap, a replan's steps included: plans are made on
// the PlanWorker's thread, which may allocate. Counts only what the thread stepping the
// loop allocates (cover/test/malloc_counter.hpp: Eigen's included; its own executable).
#include <gtest/gtest.h>

#include "cover/sim/closed_loop.hpp"
#include "cover/sim/world.hpp"
#include "cover/sim/world_uav_io.hpp"
#include "cover/test/malloc_counter.hpp"
#include "cover/uav/controller_config.hpp"
#include "cover/uav/uav_loop.hpp"

namespace {

TEST(PlanOffThread, TheControlThreadDoesNotAllocateThroughAReplan) {
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
  // The first stage's steps warm up (first solves, first plan); every later step counts,
  // the transition's and the final stage's replans included.
  while (world.state().time_s < scenario.max_duration_s &&
         !cover::mission::is_terminal(loop.task_state())) {
    const bool count = world.state().time_s > 1.0;
    const long before = cover::test::counted_allocations();
    cover::test::count_this_thread(count);
    const auto& out = loop.step(world.state().time_s, inputs, plant);
    cover::test::count_this_thread(false);
    if (count) {
      allocations += cover::test::counted_allocations() - before;
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
