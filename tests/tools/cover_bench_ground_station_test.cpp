// `cover-bench ground-station`: bad arguments are refused (exit 2) before anything starts
// (quick); one short run on a standing realtime system measures every figure, each a
// plausible number, never a zero standing for nothing (label system).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace {

using namespace std::chrono_literals;

struct BenchRun {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

BenchRun run_bench(std::vector<std::string> args, std::chrono::milliseconds timeout) {
  args.insert(args.begin(), COVER_BENCH);
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = cover::test::scratch_path("bench.stderr");
  cover::process::ChildProcess child(args, options);
  BenchRun run;
  while (const auto line = child.read_line(cover::test::scaled(timeout))) run.out += *line + "\n";
  run.exit_code = child.wait(cover::test::scaled(60s)).value_or(-1);
  std::ifstream in(options.log_file);
  std::stringstream text;
  text << in.rdbuf();
  run.err = text.str();
  return run;
}

TEST(CoverBenchGroundStation, RefusesBadArguments) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"ground-station", "--seconds", "0"},
        std::vector<std::string>{"ground-station", "--seconds", "1"},
        std::vector<std::string>{"ground-station", "--seconds", "abc"},
        std::vector<std::string>{"ground-station", "--seconds"},
        std::vector<std::string>{"ground-station", "--no-such-flag"}}) {
    const BenchRun run = run_bench(args, 30s);
    EXPECT_EQ(run.exit_code, 2) << args.back() << "\n" << run.out << run.err;
    EXPECT_TRUE(run.out.empty()) << "printed figures for " << args.back() << ":\n" << run.out;
  }
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

TEST(CoverBenchGroundStation, ShortRunMeasuresEveryFigure) {
  const BenchRun run = run_bench({"ground-station", "--seconds", "5", "--json"}, 600s);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const auto out = nlohmann::json::parse(run.out, nullptr, false);
  ASSERT_TRUE(out.is_object()) << run.out;
  EXPECT_TRUE(out["not_measured"].empty()) << run.out;
  // The state alone draws each row at 10 Hz; a loaded machine may drop some frames.
  EXPECT_GT(number(out, "slowest_row_hz"), 1.0) << run.out;
  EXPECT_GT(number(out, "page_cpu_share"), 0.0) << run.out;
  EXPECT_LT(number(out, "page_cpu_share"), 4.0) << run.out;
  EXPECT_GT(number(out, "server_cpu_share"), 0.0) << run.out;
  EXPECT_LT(number(out, "server_cpu_share"), 2.0) << run.out;
  // The probe's 10 Hz over 5 s: dozens of samples, each drawn after it was stamped.
  EXPECT_GE(number(out, "latency_samples"), 20.0) << run.out;
  EXPECT_GT(number(out, "latency_p50_ms"), 0.0) << run.out;
  EXPECT_GE(number(out, "latency_p99_ms"), number(out, "latency_p50_ms")) << run.out;
  EXPECT_LT(number(out, "latency_p99_ms"), 5000.0 * cover::test::time_scale()) << run.out;
}

}  // namespace
