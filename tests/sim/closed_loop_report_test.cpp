// The run summary (result JSON and readable lines) leaves out, or marks as not measured, a
// figure the run did not measure: as processes, cover-sim hears each SAMPC step's wall time
// and each plan's time in the UAV agent's trace, but not SAMPC's thread CPU time, and it
// runs no control step. Those were printed as "thread CPU 0 / 0 us" and "control step
// median 0 us, p99 0 us, max 0 us".
#include <gtest/gtest.h>

#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/sim/closed_loop_report.hpp"
#include "cover/sim/run_recorder.hpp"
#include "cover/sim/scenario.hpp"
#include "cover/sim/world.hpp"

namespace {

using cover::sim::ClosedLoopResult;

// Scenario 2 recorded as cover-sim records it from a UAV agent's trace: ten steps whose
// SAMPC wall time and plan time arrived, their thread CPU time not (0 on the wire).
ClosedLoopResult recorded_from_a_trace() {
  const cover::sim::Scenario scenario =
      cover::sim::Scenario::load_file(cover::sim::scenario_path("scenario2"));
  const auto mission = cover::mission::MissionParams::load_file(
      cover::config::default_config_dir() + "/mission.yaml");
  cover::sim::RunRecorder recorder(scenario, scenario.task, mission, {});
  cover::sim::World world(scenario.world);
  cover::mission::ControllerStatus status;
  for (int i = 0; i < 10; ++i) {
    status.solve_us = 40.0 + i;
    status.solve_cpu_us = 0.0;
    status.planned = i == 0;
    status.plan_ms = 3.0;
    recorder.record(status, {}, world);
  }
  return recorder.finish(world, status, "stopped", cover::mission::MissionState::Running);
}

TEST(RunSummary, FiguresTheAgentsTraceDoesNotCarryAreNotMeasuredNotZero) {
  const ClosedLoopResult r = recorded_from_a_trace();
  EXPECT_DOUBLE_EQ(r.mpc_median_us, 44.0);  // measured (rank below): the trace carries it
  EXPECT_DOUBLE_EQ(r.plan_median_ms, 3.0);

  const nlohmann::json json = cover::sim::summary_json(r);
  for (const char* key : {"mpc_cpu_median_us", "mpc_cpu_p99_us", "step_median_us", "step_p99_us",
                          "step_max_us", "plan_wait_max_ms"}) {
    EXPECT_TRUE(json[key].is_null()) << key << " = " << json[key];
  }
  for (const char* key : {"mpc_median_us", "mpc_p99_us", "plan_median_ms", "plan_max_ms"}) {
    EXPECT_TRUE(json[key].is_number()) << key << " = " << json[key];
  }

  const std::string text = cover::sim::readable_summary(r);
  EXPECT_NE(text.find("MPC step          median 44 us, p99 48 us (thread CPU not measured / not "
                      "measured)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("control step      not measured here (the UAV agent runs it)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("final tracking    not measured"), std::string::npos) << text;
  EXPECT_EQ(text.find(" 0 us"), std::string::npos) << text;
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
}

// A result nothing was recorded into measured no timing at all.
TEST(RunSummary, AnEmptyResultPrintsNoTimingAsZero) {
  const ClosedLoopResult r;
  const nlohmann::json json = cover::sim::summary_json(r);
  for (const char* key : {"mpc_median_us", "mpc_cpu_median_us", "plan_median_ms", "plan_max_ms",
                          "step_median_us", "plan_wait_max_ms"}) {
    EXPECT_TRUE(json[key].is_null()) << key << " = " << json[key];
  }
  const std::string text = cover::sim::readable_summary(r);
  EXPECT_EQ(text.find(" 0 us"), std::string::npos) << text;
  EXPECT_EQ(text.find("0.0 ms"), std::string::npos) << text;
}

}  // namespace
