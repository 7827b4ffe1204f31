// Stage plans run off the control thread (mission::PlanWorker) and are flown from a fixed
// step: a realtime step never waits for one, a lockstep step waits for the plan due at it,
// so a lockstep run is bit-identical with the machine under load (the control thread's
// and the worker's allocations through a replan: plan_allocation_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "cover/mission/mission_controller.hpp"
#include "cover/mission/plan_worker.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/test/cpu_hog.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/uav/controller_config.hpp"

namespace {

using cover::mission::MissionController;
using cover::mission::PlanClock;
using cover::mission::PlanWorker;
using namespace std::chrono_literals;

// A plan function that blocks until the test opens it: a plan as slow as the test wants.
class Gate {
 public:
  PlanWorker::PlanFunction plan_function(cover::planner::PlannerParams params) {
    PlanWorker::PlanFunction real = cover::mission::stage_plan_function(std::move(params));
    return [this, real](const cover::planner::StageProblem& problem,
                        cover::planner::PlanResult& result) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        ++entered_;
        cv_.notify_all();
        cv_.wait(lock, [&] { return open_; });
      }
      real(problem, result);
    };
  }
  void open() {
    const std::lock_guard<std::mutex> lock(mutex_);
    open_ = true;
    cv_.notify_all();
  }
  bool wait_entered(int count) {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_for(lock, cover::test::scaled(10000ms), [&] { return entered_ >= count; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  int entered_ = 0;
  bool open_ = false;
};

cover::mission::Task scenario2_task() {
  return cover::mission::load_task_file(
      cover::config::default_config_dir() + "/tasks/scenario2.yaml", 2);
}

void feed_at_rest(MissionController& controller, double t) {
  for (int k = 0; k < 2; ++k) {
    cover::mission::RelativeMeasurement state;
    state.stamp_s = t;
    controller.set_relative_state(k, state);
    cover::mission::UgvImuMeasurement imu;
    imu.stamp_s = t;
    controller.set_ugv_imu(k, imu);
  }
}

TEST(PlanOffThread, ShippedPlannerHasNoWallClockBudget) {
  // A wall-clock budget would make a plan, and a lockstep run, depend on the load.
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  EXPECT_EQ(config.planner.max_solve_time_s, 0.0);
  EXPECT_GE(config.mission.plan_adopt_steps, 1);  // the step never runs the optimiser
}

TEST(PlanOffThread, ARealtimeStepNeverWaitsForAPlan) {
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  Gate gate;
  MissionController controller(scenario2_task(), 2, config.mission, config.planner, config.sampc,
                               PlanClock::Realtime, gate.plan_function(config.planner));
  // Steps at 100 Hz while the plan cannot finish: each must return. Run on another thread
  // so that a step that blocked fails the test instead of hanging it.
  auto stepping = std::async(std::launch::async, [&] {
    int planned = 0;
    for (int k = 0; k < 20; ++k) {
      const double t = 0.01 * k;
      feed_at_rest(controller, t);
      const auto& out = controller.step(t);
      if (out.status.planned) ++planned;
      if (!out.command.armed || !std::isfinite(out.command.thrust_m_s2)) return -1;
    }
    return planned;
  });
  const bool returned =
      stepping.wait_for(cover::test::scaled(10000ms)) == std::future_status::ready;
  gate.open();  // never leave the worker (or a blocked step) waiting
  ASSERT_TRUE(returned) << "a realtime control step waited for the plan";
  EXPECT_EQ(stepping.get(), 0);  // 20 steps flown on the coasting reference
  EXPECT_TRUE(gate.wait_entered(1));
  EXPECT_TRUE(controller.plan_in_flight());
  EXPECT_TRUE(controller.output().status.reference_position_m.isZero());  // coasting at rest

  // Once it is ready, the next step adopts it, late by the steps it took, on its own clock.
  double t = 0.2;
  ASSERT_TRUE(cover::test::wait_until(
      [&] {
        feed_at_rest(controller, t);
        const bool planned = controller.step(t).status.planned;
        t += 0.01;
        return planned;
      },
      10000ms, 1ms));
  EXPECT_GE(controller.output().status.plan_late_steps, 19);
  EXPECT_DOUBLE_EQ(controller.reference_start_s(), 0.0);  // requested at step 0
  EXPECT_FALSE(controller.plan_in_flight());
}

TEST(PlanOffThread, ALockstepStepWaitsForThePlanDueAtIt) {
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  Gate gate;
  MissionController controller(scenario2_task(), 2, config.mission, config.planner, config.sampc,
                               PlanClock::Lockstep, gate.plan_function(config.planner));
  feed_at_rest(controller, 0.0);
  EXPECT_FALSE(controller.step(0.0).status.planned);  // requested; due at step 1
  ASSERT_TRUE(gate.wait_entered(1));
  // Opened from another thread once step 1 is seen waiting: step 1 flies the plan, however
  // late. (A step that did not wait returns unplanned, and is never seen waiting.)
  bool seen_waiting = false;
  std::thread opener([&] {
    seen_waiting =
        cover::test::wait_until([&] { return controller.waiting_for_plan(); }, 10000ms, 1ms);
    gate.open();
  });
  feed_at_rest(controller, 0.01);
  const auto& out = controller.step(0.01);
  opener.join();
  EXPECT_TRUE(seen_waiting) << "step 1 never waited for its plan";
  EXPECT_FALSE(controller.waiting_for_plan());
  EXPECT_TRUE(out.status.planned);
  EXPECT_EQ(out.status.plan_late_steps, 0);
  EXPECT_GT(out.status.plan_wait_ms, 0.0);
}

TEST(PlanOffThread, ANewStageSupersedesThePlanInFlight) {
  std::atomic<int> plans{0};
  PlanWorker worker(
      [&](const cover::planner::StageProblem& problem, cover::planner::PlanResult& result) {
        ++plans;
        result = cover::planner::PlanResult{};
        result.iterations = static_cast<int>(problem.goal_position_m.x());
      });
  cover::planner::StageProblem first;
  first.goal_position_m.x() = 1.0;
  cover::planner::StageProblem second;
  second.goal_position_m.x() = 2.0;
  const std::uint64_t a = worker.request(first);
  const std::uint64_t b = worker.request(second);
  cover::planner::PlanResult result;
  EXPECT_FALSE(worker.take(a, result, true));  // superseded: never returned, never waited on
  ASSERT_TRUE(worker.take(b, result, true));
  EXPECT_EQ(result.iterations, 2);
  EXPECT_FALSE(worker.take(b, result, true));  // taken once
  EXPECT_FALSE(worker.ready(b));
  // Superseded even when its plan was done before the newer request came.
  const std::uint64_t c = worker.request(first);
  ASSERT_TRUE(cover::test::wait_until([&] { return worker.ready(c); }, 10000ms, 1ms));
  const std::uint64_t d = worker.request(second);
  EXPECT_FALSE(worker.ready(c));
  EXPECT_FALSE(worker.take(c, result, true));
  ASSERT_TRUE(worker.take(d, result, true));
  EXPECT_EQ(result.iterations, 2);
}

// What a run flew, every control step: equal runs have equal traces, bit for bit.
void expect_identical(const cover::sim::ClosedLoopResult& a,
                      const cover::sim::ClosedLoopResult& b) {
  ASSERT_EQ(a.step_trace.size(), b.step_trace.size());
  for (std::size_t i = 0; i < a.step_trace.size(); ++i) {
    const cover::sim::StepSample& x = a.step_trace[i];
    const cover::sim::StepSample& y = b.step_trace[i];
    ASSERT_EQ(x.time_s, y.time_s) << "step " << i;
    ASSERT_EQ(x.stage_code, y.stage_code) << "step " << i;
    ASSERT_EQ(x.thrust_m_s2, y.thrust_m_s2) << "step " << i << " t " << x.time_s;
    ASSERT_EQ(x.body_rate_rad_s, y.body_rate_rad_s) << "step " << i << " t " << x.time_s;
    ASSERT_EQ(x.position_m, y.position_m) << "step " << i;
    ASSERT_EQ(x.reference_position_m, y.reference_position_m) << "step " << i;
  }
  EXPECT_EQ(a.success, b.success);
  EXPECT_EQ(a.duration_s, b.duration_s);
  EXPECT_EQ(a.landing_error_m, b.landing_error_m);
}

TEST(PlanOffThread, ALockstepRunIsBitIdenticalUnderACpuHog) {
  for (const cover::sampc::Mode mode : {cover::sampc::Mode::Cover, cover::sampc::Mode::Intercept}) {
    const auto config = cover::uav::ControllerConfig::load_default(mode);
    const cover::sim::Scenario scenario =
        cover::sim::Scenario::load_file(cover::sim::scenario_path("scenario2"));
    cover::sim::ClosedLoopOptions options;
    options.record_step_trace = true;
    const cover::sim::ClosedLoop loop(scenario, config, options);
    const cover::sim::ClosedLoopResult quiet = loop.run();
    ASSERT_TRUE(quiet.success) << quiet.status;
    cover::sim::ClosedLoopResult loaded;
    {
      const cover::test::CpuHog hog;
      loaded = loop.run();
    }
    SCOPED_TRACE(cover::sampc::to_string(mode));
    expect_identical(quiet, loaded);
  }
}

}  // namespace
