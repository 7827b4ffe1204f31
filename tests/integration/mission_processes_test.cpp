// Missions flown by real processes: cover-launch starts cover-sim, one cover-ugv-agent per
// UGV and the UAV agents, on Fast DDS and Cyclone DDS mixed; the result must equal the
// in-process harness's on the same seed (lockstep runs the same loop on the same inputs).
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cover/sim/closed_loop.hpp"
#include "cover/sim/closed_loop_report.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/uav/controller_config.hpp"
#include "launch_run.hpp"
#include "process_support.hpp"

namespace {

using cover::test::shm_entries;

constexpr std::chrono::seconds kRunTimeout{300};

using LaunchRun = cover::bench::LaunchOutcome;

// Each test on its own DDS domain and run folder (kept in the scratch folder when it fails).
LaunchRun launch(const std::string& file, std::vector<std::string> flags, int domain) {
  const auto claim = cover::test::claim_domain(domain);
  cover::bench::LaunchRequest request;
  request.launch_file = std::string(COVER_CONFIG_DIR) + "/launch/" + file;
  request.domain = domain;
  request.run_dir = cover::test::scratch_dir() / ("cover_it_" + std::to_string(domain));
  request.flags = std::move(flags);
  return cover::bench::run_launcher(request, "", kRunTimeout);
}

cover::sim::ClosedLoopResult in_process(const std::string& scenario_name) {
  const auto scenario = cover::sim::Scenario::load_file(cover::sim::scenario_path(scenario_name));
  cover::sim::ClosedLoopOptions options;
  options.record_paths = false;
  const cover::sim::ClosedLoop loop(
      scenario, cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover), options);
  return loop.run();
}

// Every process the launcher reports has exited and none of our segments is left.
void expect_clean(const LaunchRun& run, const std::set<std::string>& shm_before) {
  ASSERT_TRUE(run.result.contains("processes")) << run.stdout_text;
  for (const auto& p : run.result["processes"]) {
    const int pid = p["pid"].get<int>();
    EXPECT_NE(kill(pid, 0), 0) << p["name"] << " (pid " << pid << ") still runs";
  }
  for (const std::string& name : shm_entries()) {
    if (shm_before.count(name)) continue;
    EXPECT_TRUE(name.rfind("cover_sim_", 0) != 0) << "segment left: " << name;
    EXPECT_TRUE(name.find("fastrtps") == std::string::npos) << "Fast DDS file left: " << name;
  }
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

struct Mix {
  const char* name;
  std::vector<std::string> flags;
};

const Mix kUgvOnCyclone{"ugv agents on cyclone, rest on fastdds", {"--dds", "ugv*=cyclone"}};
const Mix kUgvOnFast{"ugv agents on fastdds, rest on cyclone",
                     {"--dds", "*=cyclone", "--dds", "ugv*=fastdds"}};

void expect_equals_in_process(const std::string& scenario, const Mix& mix, int domain) {
  SCOPED_TRACE(mix.name);
  const auto before = shm_entries();
  const LaunchRun run = launch(scenario + ".yaml", mix.flags, domain);
  ASSERT_EQ(run.exit_code, 0) << run.stdout_text;
  EXPECT_TRUE(run.result["success"].get<bool>()) << run.result.dump(2);
  const cover::sim::ClosedLoopResult reference = in_process(scenario);
  ASSERT_TRUE(reference.success);
  const double landing = number(run.result, "landing_error_m");
  EXPECT_NEAR(landing, reference.landing_error_m, 1e-3) << run.result.dump(2);
  if (std::isfinite(reference.delivery_error_m)) {
    EXPECT_NEAR(number(run.result, "delivery_error_m"), reference.delivery_error_m, 1e-3);
  }
  EXPECT_NEAR(number(run.result, "duration_s"), reference.duration_s, 0.011);
  // The result has every key of `cover-bench scenario --json`, with the same kind of value,
  // but for what cover-sim cannot measure as processes: SAMPC's thread CPU time (the agent's
  // trace does not carry it) and the control step (the agent runs it), null, never 0.
  const std::set<std::string> not_measured_as_processes{"mpc_cpu_median_us", "mpc_cpu_p99_us",
                                                        "step_median_us",    "step_p99_us",
                                                        "step_max_us",       "plan_wait_max_ms"};
  const nlohmann::json expected_keys = cover::sim::summary_json(reference);
  for (const auto& [key, value] : expected_keys.items()) {
    ASSERT_TRUE(run.result.contains(key)) << key;
    const nlohmann::json& got = run.result[key];
    if (not_measured_as_processes.count(key) > 0) {
      EXPECT_TRUE(got.is_null()) << key << " = " << got;
      continue;
    }
    EXPECT_TRUE(got.type() == value.type() || (got.is_number() && value.is_number())) << key;
  }
  for (const auto& p : run.result["processes"]) {
    const std::string name = p["name"];
    const bool on_cyclone = p["dds"] == "cyclone";
    EXPECT_EQ(on_cyclone, (name.rfind("ugv", 0) == 0) == (mix.flags.size() == 2)) << name;
  }
  expect_clean(run, before);
}

TEST(MissionProcesses, ScenarioTwoLockstepEqualsInProcessUgvOnCyclone) {
  expect_equals_in_process("scenario2", kUgvOnCyclone, 161);
}

TEST(MissionProcesses, ScenarioTwoLockstepEqualsInProcessUgvOnFastDds) {
  expect_equals_in_process("scenario2", kUgvOnFast, 162);
}

TEST(MissionProcesses, ScenarioFourLockstepEqualsInProcessUgvOnCyclone) {
  expect_equals_in_process("scenario4", kUgvOnCyclone, 163);
}

TEST(MissionProcesses, ScenarioFourLockstepEqualsInProcessUgvOnFastDds) {
  expect_equals_in_process("scenario4", kUgvOnFast, 164);
}

TEST(MissionProcesses, TwoUavsFlyTwoTasksInOneRun) {
  const auto before = shm_entries();
  const LaunchRun run = launch("two_uavs.yaml", {"--dds", "uav1=cyclone"}, 165);
  ASSERT_EQ(run.exit_code, 0) << run.stdout_text;
  ASSERT_TRUE(run.result.contains("uavs")) << run.result.dump(2);
  ASSERT_EQ(run.result["uavs"].size(), 2u);
  for (const auto& uav : run.result["uavs"]) {
    EXPECT_TRUE(uav["success"].get<bool>()) << uav.dump(2);
    EXPECT_LE(number(uav, "landing_error_m"), 0.05);
  }
  EXPECT_TRUE(run.result["success"].get<bool>());
  expect_clean(run, before);
}

TEST(MissionProcesses, ScenarioTwoRealtimeSucceeds) {
  const auto before = shm_entries();
  const LaunchRun run = launch("scenario2.yaml", {"--clock", "realtime"}, 166);
  ASSERT_EQ(run.exit_code, 0) << run.stdout_text;
  EXPECT_TRUE(run.result["success"].get<bool>()) << run.result.dump(2);
  EXPECT_LE(number(run.result, "landing_error_m"), 0.05);
  EXPECT_EQ(run.result["clock"], "realtime");
  ASSERT_TRUE(run.result.contains("latency_ms"));
  EXPECT_GT(run.result["latency_ms"]["samples"].get<int>(), 500);
  expect_clean(run, before);
}

}  // namespace
