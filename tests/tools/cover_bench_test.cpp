// cover-bench's paper subcommands as a user runs them: real processes, their JSON (the
// issue's interface: types and the ranges a working run meets, no claim on speed) and their
// plots.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/sampc/sampc_params.hpp"

namespace {

constexpr std::chrono::seconds kTimeout{120};

struct BenchRun {
  int exit_code = -1;
  std::string out;
};

BenchRun run_bench(std::vector<std::string> args) {
  args.insert(args.begin(), COVER_BENCH);
  cover::process::ChildProcess child(args, {}, /*capture_stdout=*/true);
  BenchRun run;
  while (const auto line = child.read_line(kTimeout)) run.out += *line + "\n";
  run.exit_code = child.wait(kTimeout).value_or(-1);
  return run;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::filesystem::path temp_dir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cover_bench_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// `value` is a finite JSON number (not null, not a string, not a bool).
::testing::AssertionResult IsFiniteNumber(const nlohmann::json& value) {
  if (!value.is_number()) return ::testing::AssertionFailure() << value << " is not a number";
  if (!std::isfinite(value.get<double>()))
    return ::testing::AssertionFailure() << value << " is not finite";
  return ::testing::AssertionSuccess();
}

// `value` is a finite number in [lo, hi].
::testing::AssertionResult IsNumberIn(const nlohmann::json& value, double lo, double hi) {
  if (auto finite = IsFiniteNumber(value); !finite) return finite;
  const double v = value.get<double>();
  if (v < lo || v > hi)
    return ::testing::AssertionFailure() << v << " is outside [" << lo << ", " << hi << "]";
  return ::testing::AssertionSuccess();
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// Every method SAMPC has (kModes' names): each comparison bench runs them all.
std::set<std::string> all_methods() {
  std::set<std::string> names;
  for (const cover::sampc::Mode mode : cover::sampc::kModes)
    names.insert(cover::sampc::to_string(mode));
  return names;
}
const std::set<std::string> kMethods = all_methods();

}  // namespace

TEST(CoverBench, Table1PrintsEveryMethodAndPlotsEachRun) {
  const auto svg = temp_dir() / "t1.svg";
  const BenchRun run = run_bench({"table1", "--v", "0.5", "--w", "0.35", "--transitions", "1",
                                  "--phases", "2", "--json", "--plot", svg.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto out = nlohmann::json::parse(run.out);
  EXPECT_EQ(out["transitions_per_run"], 1);
  EXPECT_EQ(out["runs_per_row"], 2);
  EXPECT_EQ(out["plot"], svg.string());
  ASSERT_EQ(out["rows"].size(), kMethods.size());
  std::set<std::string> methods;
  for (const auto& row : out["rows"]) {
    SCOPED_TRACE(row["method"].dump());
    ASSERT_TRUE(row["method"].is_string());
    methods.insert(row["method"].get<std::string>());
    EXPECT_EQ(row["v"], 0.5);
    EXPECT_EQ(row["w"], 0.35);
    EXPECT_EQ(row["transitions"], 2);
    EXPECT_EQ(row["failures"], 0);
    // Two transitions of a few metres each; a path is never shorter than the straight line.
    EXPECT_TRUE(IsNumberIn(row["Ls"], 2.0, 20.0));
    EXPECT_TRUE(IsNumberIn(row["Lt"], row["Ls"].get<double>(), 40.0));
    EXPECT_TRUE(IsNumberIn(row["ratio"], 1.0, 2.0));
    EXPECT_NEAR(row["ratio"].get<double>(), row["Lt"].get<double>() / row["Ls"].get<double>(),
                1e-12);
    EXPECT_TRUE(IsNumberIn(row["eq30_law_ratio"], 1.0, 2.0));
    EXPECT_TRUE(IsFiniteNumber(row["realtime_factor"]));
    EXPECT_GT(row["realtime_factor"].get<double>(), 0.0);
    ASSERT_EQ(row["statuses"].size(), 2u);  // one per phase
    for (const auto& status : row["statuses"]) {
      EXPECT_TRUE(starts_with(status.get<std::string>(), "complete")) << status;
    }
    ASSERT_EQ(row["per_transition"].size(), 2u);
    double ls = 0.0;
    for (const auto& t : row["per_transition"]) {
      EXPECT_EQ(t["completed"], true);
      EXPECT_EQ(t["from"], 0);
      EXPECT_EQ(t["to"], 1);
      EXPECT_TRUE(IsNumberIn(t["duration_s"], 0.1, 60.0));
      EXPECT_TRUE(IsNumberIn(t["Lt"], t["Ls"].get<double>(), 20.0));
      ls += t["Ls"].get<double>();
    }
    EXPECT_NEAR(ls, row["Ls"].get<double>(), 1e-9);  // the row sums its transitions
  }
  EXPECT_EQ(methods, kMethods);
  // The plot names its setting and method in the title.
  EXPECT_NE(read_file(svg).find("Table 1, v = 0.50 m/s, w = 0.35 rad/s: cover"), std::string::npos);
  EXPECT_NE(read_file(temp_dir() / "t1_coni-mpc.svg").find("rad/s: coni-mpc"), std::string::npos);
  EXPECT_NE(read_file(temp_dir() / "t1_no-ref-vxy.svg").find("rad/s: no-ref-vxy"),
            std::string::npos);
  std::filesystem::remove_all(temp_dir());
}

TEST(CoverBench, ScenarioTwoReportsTheIssueKeys) {
  const BenchRun run = run_bench({"scenario", "2", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto out = nlohmann::json::parse(run.out);
  EXPECT_EQ(out["scenario"], 2);
  EXPECT_EQ(out["method"], "cover");
  EXPECT_EQ(out["success"], true);
  ASSERT_TRUE(out["status"].is_string());
  EXPECT_TRUE(starts_with(out["status"].get<std::string>(), "complete")) << out["status"];
  EXPECT_TRUE(IsNumberIn(out["landing_error_m"], 0.0, 0.05));
  EXPECT_TRUE(out["delivery_error_m"].is_null());  // Scenario 2 delivers nothing
  ASSERT_EQ(out["tracking_error_m"].size(), 3u);
  for (const auto& axis : out["tracking_error_m"]) EXPECT_TRUE(IsNumberIn(axis, 0.0, 0.1));
  EXPECT_EQ(out["transitions"], 1);
  EXPECT_EQ(out["failsafe_steps"], 0);
  EXPECT_TRUE(IsNumberIn(out["ratio"], 1.0, 3.0));
  // Take-off, one transition and a landing: seconds, well inside the scenario's limit.
  EXPECT_TRUE(IsNumberIn(out["duration_s"], 1.0, 60.0));
  // Timings: measured, finite and positive (no claim on speed).
  for (const char* key :
       {"realtime_factor", "mpc_median_us", "mpc_p99_us", "plan_median_ms", "plan_max_ms"}) {
    EXPECT_TRUE(IsFiniteNumber(out[key])) << key;
    EXPECT_GT(out[key].get<double>(), 0.0) << key;
  }
  EXPECT_GE(out["mpc_p99_us"].get<double>(), out["mpc_median_us"].get<double>());
  EXPECT_GE(out["plan_max_ms"].get<double>(), out["plan_median_ms"].get<double>());
}

TEST(CoverBench, StabilityRowsPerMethod) {
  const BenchRun run = run_bench({"stability", "--pattern", "circle", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto out = nlohmann::json::parse(run.out);
  EXPECT_TRUE(IsNumberIn(out["window_s"], 0.1, 10.0));
  const auto& rows = out["rows"];
  ASSERT_EQ(rows.size(), kMethods.size());
  std::set<std::string> methods;
  for (const auto& row : rows) {
    SCOPED_TRACE(row["method"].dump());
    ASSERT_TRUE(row["method"].is_string());
    methods.insert(row["method"].get<std::string>());
    EXPECT_EQ(row["pattern"], "circle");
    EXPECT_TRUE(starts_with(row["status"].get<std::string>(), "complete")) << row["status"];
    // Every method switches frames on the circle: the changes are measured, >= 0 and
    // bounded by the command limits (rad/s per step, m/s^2 per step); speeds are m/s.
    EXPECT_TRUE(IsNumberIn(row["peak_rate_change"], 0.0, 10.0));
    EXPECT_TRUE(IsNumberIn(row["rms_rate_change"], 0.0, row["peak_rate_change"].get<double>()));
    EXPECT_TRUE(IsNumberIn(row["peak_thrust_change"], 0.0, 30.0));
    EXPECT_TRUE(IsNumberIn(row["peak_world_speed"], 0.1, 10.0));
  }
  EXPECT_EQ(methods, kMethods);
}

TEST(CoverBench, BadArgumentsAreUsageErrors) {
  EXPECT_NE(run_bench({"table1", "--v", "0.5"}).exit_code, 0);  // --v needs --w
  EXPECT_NE(run_bench({"table1", "--method", "pid"}).exit_code, 0);
  EXPECT_NE(run_bench({"scenario", "7"}).exit_code, 0);
  EXPECT_NE(run_bench({"scenario", "2", "--method", "pid"}).exit_code, 0);
  EXPECT_NE(run_bench({"stability", "--pattern", "spiral"}).exit_code, 0);
  EXPECT_NE(run_bench({"mpc", "--mode", "pid"}).exit_code, 0);
}
