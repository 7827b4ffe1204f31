// cover-bench's paper subcommands as a user runs them: real processes, their JSON (the
// issue's interface: types and the ranges a working run meets, no claim on speed) and their
// plots.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/process/stop_children_on_shutdown.hpp"
#include "cover/sampc/sampc_params.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vocabulary/angles.hpp"

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

const std::filesystem::path& temp_dir() {
  return cover::test::scratch_dir();
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

// Every SAMPC method (cover::sampc::kModes): the benchmarks run them all by default.
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
  const auto transitions_svg = temp_dir() / "t1_transitions.svg";
  const BenchRun run =
      run_bench({"table1", "--v", "0.5", "--w", "0.35", "--transitions", "1", "--runs", "2",
                 "--json", "--plot", svg.string(), "--plot-transitions", transitions_svg.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto out = nlohmann::json::parse(run.out);
  EXPECT_EQ(out["transitions_per_run"], 1);
  EXPECT_EQ(out["sampling"], "uniform");
  EXPECT_EQ(out["sample_seed"], 1);
  EXPECT_EQ(out["runs_per_row"], 2);
  EXPECT_EQ(out["plot"], svg.string());
  EXPECT_EQ(out["transitions_plot"], transitions_svg.string());
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
    // The shortest paths within the limits: straight at best, never above what was flown.
    EXPECT_TRUE(IsNumberIn(row["bound_ratio"], 1.0, row["ratio"].get<double>()));
    EXPECT_EQ(row["bound_unreached"], 0);
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
      EXPECT_EQ(t["bound_reached"], true);
      EXPECT_TRUE(IsNumberIn(t["bound_Lt"], t["bound_Ls"].get<double>(), t["Lt"].get<double>()));
      EXPECT_TRUE(IsNumberIn(t["bound_arrival_s"], 0.1, t["duration_s"].get<double>()));
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
  // One transition per method in one picture, with the bound.
  const std::string transitions = read_file(transitions_svg);
  for (const std::string& method : kMethods)
    EXPECT_NE(transitions.find(method + ": UAV"), std::string::npos) << method;
  EXPECT_NE(transitions.find("shortest path (bound)"), std::string::npos);
}

std::vector<std::pair<double, double>> run_phases(const nlohmann::json& out) {
  std::vector<std::pair<double, double>> phases;
  for (const auto& p : out["run_phases_rad"]) phases.emplace_back(p[0], p[1]);
  return phases;
}

// Uniform sampling draws both UGVs' phases over the whole turn, the same draws for every
// method, other draws for another --sample-seed; stepped keeps G0 and steps G1.
TEST(CoverBench, Table1SamplesStartingPhases) {
  const std::vector<std::string> base = {"table1",        "--v", "0.5",    "--w",    "0.35",
                                         "--transitions", "1",   "--json", "--runs", "8"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    const BenchRun run = run_bench(args);
    EXPECT_EQ(run.exit_code, 0) << run.out;
    return nlohmann::json::parse(run.out);
  };
  const auto cover = with({"--method", "cover"});
  const auto coni = with({"--method", "coni-mpc"});
  const auto other_seed = with({"--method", "cover", "--sample-seed", "2"});
  const auto phases = run_phases(cover);
  ASSERT_EQ(phases.size(), 8u);
  EXPECT_EQ(phases, run_phases(coni));
  EXPECT_NE(phases, run_phases(other_seed));
  double g0_lo = cover::model::kTwoPi, g0_hi = 0.0, g1_lo = cover::model::kTwoPi, g1_hi = 0.0;
  for (const auto& [g0, g1] : phases) {
    EXPECT_TRUE(g0 >= 0.0 && g0 < cover::model::kTwoPi && g1 >= 0.0 && g1 < cover::model::kTwoPi)
        << g0 << ", " << g1;
    g0_lo = std::min(g0_lo, g0), g0_hi = std::max(g0_hi, g0);
    g1_lo = std::min(g1_lo, g1), g1_hi = std::max(g1_hi, g1);
  }
  // Eight uniform draws spread over more than half a turn for each UGV.
  EXPECT_GT(g0_hi - g0_lo, 0.5 * cover::model::kTwoPi);
  EXPECT_GT(g1_hi - g1_lo, 0.5 * cover::model::kTwoPi);
  EXPECT_EQ(cover["rows"][0]["transitions"], 8);

  const auto stepped = with({"--method", "cover", "--sampling", "stepped", "--phases", "3"});
  EXPECT_EQ(stepped["sampling"], "stepped");
  const auto steps = run_phases(stepped);
  ASSERT_EQ(steps.size(), 3u);
  for (std::size_t i = 1; i < steps.size(); ++i) {
    EXPECT_DOUBLE_EQ(steps[i].first, steps[0].first);
    EXPECT_NEAR(steps[i].second - steps[0].second, cover::model::kTwoPi * i / 3.0, 1e-12);
  }
}

// Scenario 1 on both of the paper's patterns (and the short lines), each beside its Table 3
// value; the lines' transitions as long as the paper's (L_s per transition within 15 %).
TEST(CoverBench, ScenarioOneOnCirclesAndLines) {
  for (const auto& [pattern, paper] : std::vector<std::pair<std::string, double>>{
           {"circle", 1.11}, {"lines", 1.07}, {"lines-short", 1.07}}) {
    SCOPED_TRACE(pattern);
    const BenchRun run = run_bench({"scenario", "1", "--pattern", pattern, "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.out;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_EQ(out["pattern"], pattern);
    EXPECT_EQ(out["paper_ratio"], paper);
    EXPECT_EQ(out["success"], true);
    EXPECT_EQ(out["transitions"], 8);
    EXPECT_TRUE(IsNumberIn(out["ratio"], 1.0, 2.0));
    EXPECT_TRUE(IsNumberIn(out["bound_ratio"], 1.0, out["ratio"].get<double>()));
    for (const auto& axis : out["tracking_error_m"]) EXPECT_TRUE(IsNumberIn(axis, 0.0, 0.05));
    const double paper_length = out["paper_transition_length_m"].get<double>();
    EXPECT_NEAR(paper_length, (pattern == "circle" ? 55.68 : 57.67) / 8.0, 1e-12);
    if (pattern == "lines") {
      EXPECT_TRUE(IsNumberIn(out["transition_length_m"], 0.85 * paper_length, paper_length));
    }
  }
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
  EXPECT_NE(run_bench({"scenario", "2", "--pattern", "lines"}).exit_code, 0);  // scenario 1's
  EXPECT_NE(run_bench({"scenario", "1", "--pattern", "spiral"}).exit_code, 0);
  EXPECT_NE(run_bench({"table1", "--sampling", "random"}).exit_code, 0);
  EXPECT_NE(run_bench({"stability", "--pattern", "spiral"}).exit_code, 0);
  EXPECT_NE(run_bench({"mpc", "--mode", "pid"}).exit_code, 0);
  // Rejected before any process or network namespace is started.
  EXPECT_NE(run_bench({"faults", "--mix", "opendds"}).exit_code, 0);
  EXPECT_NE(run_bench({"faults", "--fault", "meteor"}).exit_code, 0);
  EXPECT_NE(run_bench({"faults", "--count", "0"}).exit_code, 0);
  EXPECT_NE(run_bench({"wifi", "--seeds", "0"}).exit_code, 0);
}

// SIGTERM to cover-bench alone while its launch runs (`respawn`: a standing system of the
// simulator, the agents and the task manager): the launch is stopped as a signal asks it and
// removes the simulator's shared memory, every process of the run ends, and cover-bench exits
// 130. Killed with cover-bench (PR_SET_PDEATHSIG), the launch left its segment behind.
TEST(CoverBench, ASignalStopsItsLaunchAndLeavesNothingBehind) {
  namespace fs = std::filesystem;
  cover::process::SpawnOptions options;
  options.extra_env = {"TMPDIR=" + temp_dir().string()};
  options.log_file = cover::test::scratch_path("respawn.log");
  cover::process::ChildProcess bench({COVER_BENCH, "respawn"}, options);
  const auto launch_of = [&]() -> pid_t {
    for (const pid_t pid : cover::process::live_children(bench.pid())) {
      std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
      std::string name;
      if (std::getline(comm, name) && name == "cover-launch") return pid;
    }
    return 0;
  };
  const auto segment_of = [](pid_t launch) {
    const std::string suffix = "_" + std::to_string(launch);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator("/dev/shm", ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("cover_sim_", 0) == 0 && name.size() > suffix.size() &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        return name;
    }
    return std::string();
  };
  pid_t launch = 0;
  std::vector<pid_t> run;  // the launch's processes
  ASSERT_TRUE(cover::test::wait_until(
      [&] {
        launch = launch_of();
        run = launch ? cover::process::live_children(launch) : std::vector<pid_t>{};
        return launch != 0 && !segment_of(launch).empty() && run.size() >= 4;
      },
      std::chrono::seconds(90)))
      << "no launch with its segment and processes; " << read_file(options.log_file);
  const std::string segment = segment_of(launch);
  ASSERT_EQ(kill(bench.pid(), SIGTERM), 0);
  EXPECT_EQ(bench.wait(cover::test::scaled(std::chrono::seconds(30))), std::optional<int>(130))
      << read_file(options.log_file);
  EXPECT_FALSE(fs::exists("/dev/shm/" + segment)) << segment << " left behind";
  for (const pid_t pid : run) {
    EXPECT_TRUE(cover::test::wait_until([&] { return kill(pid, 0) != 0; }, std::chrono::seconds(5)))
        << "process " << pid << " of the run still there";
  }
  EXPECT_NE(read_file(options.log_file).find("stopping on a signal"), std::string::npos);
}
