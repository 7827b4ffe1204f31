// cover-bench's paper subcommands as a user runs them: real processes, their JSON keys
// (the issue's interface) and their plots.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"

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

}  // namespace

TEST(CoverBench, Table1PrintsEveryMethodAndPlotsEachRun) {
  const auto svg = temp_dir() / "t1.svg";
  const BenchRun run = run_bench({"table1", "--v", "0.5", "--w", "0.35", "--transitions", "1",
                                  "--phases", "2", "--json", "--plot", svg.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto out = nlohmann::json::parse(run.out);
  ASSERT_EQ(out["rows"].size(), 3u);
  EXPECT_EQ(out["runs_per_row"], 2);
  for (const auto& row : out["rows"]) {
    for (const char* key :
         {"v", "w", "method", "Ls", "Lt", "ratio", "transitions", "failures", "eq30_law_ratio"}) {
      EXPECT_TRUE(row.contains(key)) << key;
    }
    EXPECT_EQ(row["transitions"], 2);
    EXPECT_EQ(row["failures"], 0);
    EXPECT_GE(row["ratio"].get<double>(), 1.0);
  }
  // The plot names its setting and method in the title (a mangled title once slipped by).
  EXPECT_NE(read_file(svg).find("Table 1, v = 0.50 m/s, w = 0.35 rad/s: cover"), std::string::npos);
  EXPECT_NE(read_file(temp_dir() / "t1_coni-mpc.svg").find("rad/s: coni-mpc"), std::string::npos);
  std::filesystem::remove_all(temp_dir());
}

TEST(CoverBench, ScenarioTwoReportsTheIssueKeys) {
  const BenchRun run = run_bench({"scenario", "2", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto out = nlohmann::json::parse(run.out);
  EXPECT_EQ(out["success"], true);
  EXPECT_LE(out["landing_error_m"].get<double>(), 0.05);
  EXPECT_TRUE(out["delivery_error_m"].is_null());  // Scenario 2 delivers nothing
  EXPECT_EQ(out["tracking_error_m"].size(), 3u);
  EXPECT_GT(out["duration_s"].get<double>(), 0.0);
  EXPECT_GT(out["realtime_factor"].get<double>(), 0.0);
}

TEST(CoverBench, StabilityRowsPerMethod) {
  const BenchRun run = run_bench({"stability", "--pattern", "circle", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto rows = nlohmann::json::parse(run.out)["rows"];
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& row : rows) {
    EXPECT_EQ(row["pattern"], "circle");
    for (const char* key : {"method", "peak_rate_change", "rms_rate_change", "peak_thrust_change",
                            "peak_world_speed"}) {
      EXPECT_TRUE(row.contains(key)) << key;
    }
  }
}

TEST(CoverBench, BadArgumentsAreUsageErrors) {
  EXPECT_NE(run_bench({"table1", "--v", "0.5"}).exit_code, 0);  // --v needs --w
  EXPECT_NE(run_bench({"table1", "--method", "pid"}).exit_code, 0);
  EXPECT_NE(run_bench({"scenario", "7"}).exit_code, 0);
  EXPECT_NE(run_bench({"stability", "--pattern", "spiral"}).exit_code, 0);
}
