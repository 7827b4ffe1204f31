// Every cover-bench subcommand pointed at something that yields nothing refuses to report it
// as a result: a non-zero exit and, on stderr, what it did not measure and why; a figure it
// did not measure is null in its JSON, never 0. Cheap on purpose: arguments that ask for
// nothing, worlds in which the measured event never happens, and launch files whose
// "mission" only writes a successful result.json (COVER_CONFIG_DIR pointed at a copy of
// config/ with stand-in launch files), which is what a run looks like to a benchmark when
// its measuring side hears nothing (issue 31: `cover-bench mocap` compared nothing and
// exited 0).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cover/config/yaml_reader.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr int kUsage = 2;
constexpr int kRunFailed = 1;
constexpr int kScenarioFailed = 3;
constexpr int kNotMeasured = 4;

struct BenchRun {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `cover-bench ARGS` to its end, with `env` ("KEY=value") added.
BenchRun run_bench(std::vector<std::string> args, const std::vector<std::string>& env = {}) {
  static int count = 0;
  args.insert(args.begin(), COVER_BENCH);
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.extra_env = env;
  options.log_file = cover::test::scratch_path("bench_" + std::to_string(++count) + ".stderr");
  cover::process::ChildProcess child(args, options);
  BenchRun run;
  while (const auto line = child.read_line(cover::test::scaled(120s))) run.out += *line + "\n";
  run.exit_code = child.wait(cover::test::scaled(120s)).value_or(-1);
  run.err = read_text(options.log_file);
  return run;
}

// The reason a subcommand gives for what it did not measure.
::testing::AssertionResult SaysNotMeasured(const BenchRun& run, const std::string& reason) {
  const std::string line = "not measured: ";
  if (run.err.find(line) == std::string::npos || run.err.find(reason) == std::string::npos) {
    return ::testing::AssertionFailure()
           << "stderr names no 'not measured: ... " << reason << "':\n"
           << run.err;
  }
  return ::testing::AssertionSuccess();
}

// A copy of the shipped config/ in the scratch folder, for COVER_CONFIG_DIR.
fs::path config_copy(const std::string& name) {
  const fs::path dir = cover::test::scratch_dir() / name;
  fs::remove_all(dir);
  fs::copy(cover::config::default_config_dir(), dir, fs::copy_options::recursive);
  return dir;
}

// A launch file whose "simulator" writes {"success": true, "landing_error_m": 0.01} as its
// result and ends the run, beside two idle stand-ins named as the agents (the benchmarks'
// --dds overrides name them); `variables` declares what the benchmark passes with --var.
void write_stand_in_launch(const fs::path& config, const std::string& name,
                           const std::string& variables) {
  std::ofstream(config / "launch" / (name + ".yaml"))
      << "launch:\n  name: " << name << "\n  grace_period_s: 0.3\n"
      << "  variables: {clock: lockstep, seed: \"\", method: \"\"" << variables << "}\n"
      << "  processes:\n"
      << "    - name: sim\n      executable: /bin/sh\n"
      << "      args: [-c, 'printf \"\\173\\\"success\\\": true, \\\"landing_error_m\\\": "
         "0.01\\175\" > {run_dir}/result.json']\n"
      << "      ends_run: true\n"
      << "    - {name: ugv0, executable: /bin/sleep, args: [\"30\"]}\n"
      << "    - {name: uav0, executable: /bin/sleep, args: [\"30\"]}\n";
}

std::string config_env(const fs::path& config) {
  return "COVER_CONFIG_DIR=" + config.string();
}

// --- subcommands that measure in this process ---

TEST(CoverBenchRefusal, DdsWithNoRoundTripAskedForRefuses) {
  const BenchRun run = run_bench({"dds", "--count", "0", "--paced-count", "0", "--json"});
  EXPECT_EQ(run.exit_code, kNotMeasured) << run.out << run.err;
  EXPECT_TRUE(SaysNotMeasured(run, "no round trip asked for"));
}

// Arguments that would measure nothing are usage errors before anything runs.
TEST(CoverBenchRefusal, ArgumentsThatAskForNothingAreUsageErrors) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"planner", "--problems", "0"},
           {"sim", "--steps", "0"},
           {"mpc", "--iterations", "0"},
           {"fc", "--samples", "0"},
           {"tasks", "--tasks", "0"},
           {"record", "--duration", "0"},
           {"faults", "--count", "0"},
           {"wifi", "--seeds", "0"},
           {"table1", "--runs", "0"},
           {"fleet", "--uavs", "0"},
           {"fleet", "--uavs", "3"},
           {"discovery", "--processes", "1"},
           {"firmware-world", "--seeds", "0", "--realtime", "0"},
           {"faults", "--firmware", "px4", "--fault", "sim_kill"}}) {
    SCOPED_TRACE(args[0]);
    const BenchRun run = run_bench(args);
    EXPECT_EQ(run.exit_code, kUsage) << run.err;
  }
}

// The optimality gap not asked for is left out (null), not reported as a gap of 0.
TEST(CoverBenchRefusal, MpcWithoutGapProblemsLeavesTheGapOut) {
  const BenchRun run = run_bench({"mpc", "--iterations", "20", "--gap-problems", "0", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto out = nlohmann::json::parse(run.out);
  for (const char* key : {"optimality_gap", "optimality_gap_median", "optimality_gap_hover_start",
                          "gap_kkt_gradient_max"}) {
    EXPECT_TRUE(out[key].is_null()) << key << " = " << out[key];
  }
  EXPECT_TRUE(out["median_us"].is_number());
}

// UGVs too fast and too far apart for the UAV: no transition completes, so no L_t/L_s.
TEST(CoverBenchRefusal, Table1WithoutACompletedTransitionRefuses) {
  const BenchRun run =
      run_bench({"table1", "--v", "5", "--w", "0.1", "--separation-m", "50", "--runs", "1",
                 "--transitions", "1", "--method", "cover", "--json"});
  EXPECT_EQ(run.exit_code, kNotMeasured) << run.out << run.err;
  EXPECT_TRUE(SaysNotMeasured(run, "none of 1 transitions completed"));
  const auto row = nlohmann::json::parse(run.out)["rows"][0];
  EXPECT_TRUE(row["ratio"].is_null()) << row;
  EXPECT_TRUE(row["Ls"].is_null()) << row;
  EXPECT_EQ(row["transitions"], 0);
}

// The initial point out of reach within the run: the frame never switches.
TEST(CoverBenchRefusal, StabilityWithoutAFrameSwitchRefuses) {
  const fs::path config = config_copy("config_unreachable");
  const fs::path task = config / "tasks" / "table1.yaml";
  std::string text = read_text(task);
  const std::string first = "initial_point_m: [0, 0, 1.5]";
  ASSERT_NE(text.find(first), std::string::npos);
  text.replace(text.find(first), first.size(), "initial_point_m: [0, 0, 100.0]");
  std::ofstream(task) << text;
  const BenchRun run =
      run_bench({"stability", "--pattern", "circle", "--json"}, {config_env(config)});
  EXPECT_EQ(run.exit_code, kNotMeasured) << run.out << run.err;
  EXPECT_TRUE(SaysNotMeasured(run, "the frame never switched"));
  for (const auto& row : nlohmann::json::parse(run.out)["rows"]) {
    EXPECT_TRUE(row["peak_rate_change"].is_null()) << row;
  }
}

// Already so before issue 31: a scenario that does not complete fails (exit 3).
TEST(CoverBenchRefusal, ScenarioCutShortFails) {
  const fs::path file = cover::test::scratch_path("scenario2_1s.yaml");
  std::string text = read_text(cover::config::default_config_dir() + "/scenarios/scenario2.yaml");
  const auto cut = text.find("max_duration_s:");
  ASSERT_NE(cut, std::string::npos);
  text.replace(cut, text.find('\n', cut) - cut, "max_duration_s: 1.0");
  const std::string task = "task_file: ../tasks/";
  ASSERT_NE(text.find(task), std::string::npos);
  text.replace(text.find(task), task.size(),
               "task_file: " + cover::config::default_config_dir() + "/tasks/");
  std::ofstream(file) << text;
  const BenchRun run = run_bench({"scenario", "2", "--scenario-file", file.string()});
  EXPECT_EQ(run.exit_code, kScenarioFailed) << run.out;
  EXPECT_NE(run.out.find("FAILED"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("nan"), std::string::npos) << "a figure printed as nan:\n" << run.out;
}

// --- subcommands that measure a launch ---

// Issue 31's report: a mocap run whose flight "succeeded" while the benchmark compared no
// relative state with the truth exited 0 with every figure 0.
TEST(CoverBenchRefusal, MocapThatComparesNothingRefuses) {
  const fs::path config = config_copy("config_stand_in_mocap");
  write_stand_in_launch(config, "scenario2_mocap", ", mocap_port: \"3883\", mocap_config: \"\"");
  const BenchRun run = run_bench({"mocap", "--clock", "lockstep", "--json"}, {config_env(config)});
  EXPECT_EQ(run.exit_code, kNotMeasured) << run.out << run.err;
  EXPECT_TRUE(SaysNotMeasured(run, "no relative state compared with the truth"));
  EXPECT_TRUE(SaysNotMeasured(run, "relay latency"));
  const auto rows = nlohmann::json::parse(run.out)["mocap"];
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    EXPECT_EQ(row["success"], true) << row;  // the stand-in's result: a "successful" flight
    EXPECT_EQ(row["compared"], 0) << row;
    for (const char* key : {"position_error_p99_m", "velocity_error_p99_m_s", "valid_fraction",
                            "relay_latency_p99_ms"}) {
      EXPECT_TRUE(row[key].is_null()) << key << ": " << row;
    }
  }
}

TEST(CoverBenchRefusal, FcLatencyWithoutASampleRefuses) {
  const fs::path config = config_copy("config_stand_in_fc");
  write_stand_in_launch(config, "scenario2_px4",
                        ", fc_port: \"\", autopilot_port: \"\", ugv0_imu_port: \"\", "
                        "ugv1_imu_port: \"\", ugv_autopilot_port: \"\"");
  const BenchRun run = run_bench({"fc", "--runs", "1", "--samples", "10", "--batch", "1", "--json"},
                                 {config_env(config)});
  EXPECT_EQ(run.exit_code, kNotMeasured) << run.out << run.err;
  EXPECT_TRUE(SaysNotMeasured(run, "latency through px4"));
  const auto latency = nlohmann::json::parse(run.out)["latency"][0];
  EXPECT_TRUE(latency["p50_ms"].is_null()) << latency;
  EXPECT_EQ(latency["samples"], 0) << latency;
}

TEST(CoverBenchRefusal, E2eWithoutALatencySampleRefuses) {
  const fs::path config = config_copy("config_stand_in_e2e");
  write_stand_in_launch(config, "scenario2", "");
  write_stand_in_launch(config, "scenario4", "");
  const BenchRun run = run_bench({"e2e", "--no-floor", "--json"}, {config_env(config)});
  EXPECT_EQ(run.exit_code, kNotMeasured) << run.out << run.err;
  EXPECT_TRUE(SaysNotMeasured(run, "latency, fastdds plain"));
  EXPECT_TRUE(SaysNotMeasured(run, "lockstep scenario4"));
  const auto out = nlohmann::json::parse(run.out);
  for (const auto& row : out["latency"]) EXPECT_TRUE(row["p50_ms"].is_null()) << row;
  for (const auto& row : out["lockstep"]) EXPECT_TRUE(row["speed_factor"].is_null()) << row;
}

// Already so before issue 31 (after 30 s): a simulator that cannot start fails the run, now
// as soon as it has exited, naming its exit and log.
TEST(CoverBenchRefusal, FaultsWithoutASimulatorFails) {
  const fs::path empty = cover::test::scratch_dir() / "config_empty";
  fs::create_directories(empty);
  const BenchRun run = run_bench(
      {"faults", "--fault", "uav_agent_kill", "--count", "1", "--mix", "fastdds", "--json"},
      {config_env(empty)});
  EXPECT_EQ(run.exit_code, kRunFailed) << run.out << run.err;
  EXPECT_NE(run.err.find("cover-sim exited with code"), std::string::npos) << run.err;
}

}  // namespace
