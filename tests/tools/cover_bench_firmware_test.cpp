// `cover-bench firmware`: without the firmware it refuses (exit 4, the variable to set named);
// with PX4 SITL (COVER_PX4_SITL, label firmware) one short run measures every figure, and
// each is plausible: the bridge's 100 Hz reaches the firmware, latencies are finite and
// positive, the agent-silent land is within 150 ms, the firmware's own failsafe acts after
// COM_OF_LOSS_T.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cover/firmware/firmware_build.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace {

using namespace std::chrono_literals;

constexpr int kNotMeasured = 4;

struct BenchRun {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// `cover-bench ARGS` to its end, with `env` ("KEY=value") added.
BenchRun run_bench(std::vector<std::string> args, const std::vector<std::string>& env,
                   std::chrono::milliseconds timeout) {
  args.insert(args.begin(), COVER_BENCH);
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.extra_env = env;
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

double number(const nlohmann::json& j, const std::string& a, const std::string& b) {
  if (!j.contains(a) || !j[a].contains(b) || !j[a][b].is_number()) return NAN;
  return j[a][b].get<double>();
}

const nlohmann::json* fault(const nlohmann::json& autopilot, const std::string& name) {
  if (!autopilot.contains("faults")) return nullptr;
  for (const auto& f : autopilot.at("faults")) {
    if (f.value("fault", "") == name) return &f;
  }
  return nullptr;
}

TEST(CoverBenchFirmware, WithoutTheFirmwareRefusesNamingTheVariable) {
  const std::string nowhere = (cover::test::scratch_dir() / "no-px4-here").string();
  const BenchRun run =
      run_bench({"firmware", "--autopilot", "px4", "--json"}, {"COVER_PX4_SITL=" + nowhere}, 60s);
  EXPECT_EQ(run.exit_code, kNotMeasured) << run.err;
  EXPECT_NE(run.err.find("not measured: px4"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("COVER_PX4_SITL"), std::string::npos) << run.err;
  const auto out = nlohmann::json::parse(run.out, nullptr, false);
  ASSERT_FALSE(out.is_discarded()) << run.out;
  EXPECT_TRUE(out["autopilots"].empty()) << run.out;
  EXPECT_EQ(out["not_measured"].size(), 1u) << run.out;
}

TEST(CoverBenchFirmware, Px4SihShortRunMeasuresEveryFigure) {
  const auto lookup = cover::firmware::find_px4_sitl();
  if (!lookup.build) {
    if (cover::firmware::firmware_required()) {
      FAIL() << lookup.missing << " (COVER_REQUIRE_FIRMWARE=1)";
    }
    GTEST_SKIP() << lookup.missing;
  }
  const BenchRun run = run_bench(
      {"firmware", "--autopilot", "px4", "--tries", "1", "--hold-s", "5", "--json"}, {}, 240s);
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;  // the JSON: each try's detail
  const auto out = nlohmann::json::parse(run.out, nullptr, false);
  ASSERT_FALSE(out.is_discarded()) << run.out;
  ASSERT_EQ(out["autopilots"].size(), 1u) << run.out;
  const nlohmann::json& ap = out["autopilots"][0];
  EXPECT_EQ(ap.value("autopilot", ""), "px4");
  // The agent's 100 Hz reaches the firmware.
  EXPECT_GT(number(ap, "setpoint_rate_hz", "median"), 50.0) << ap.dump(2);
  EXPECT_GT(number(ap, "setpoint_rate_hz", "worst_window"), 50.0) << ap.dump(2);
  for (const char* key : {"to_firmware_p50", "to_firmware_p99", "echo_p50", "echo_p99"}) {
    const double ms = number(ap, "latency_ms", key);
    EXPECT_TRUE(std::isfinite(ms) && ms > 0.0 && ms < 1000.0) << key << ": " << ap.dump(2);
  }
  EXPECT_LE(number(ap, "latency_ms", "echo_p50"), number(ap, "latency_ms", "echo_p99"));
  const double hover_error = number(ap, "hover", "error_percent");
  EXPECT_TRUE(std::isfinite(hover_error) && hover_error < 20.0) << ap.dump(2);
  const double rise = number(ap, "rate_step", "rise_90_ms");
  EXPECT_TRUE(std::isfinite(rise) && rise > 0.0 && rise < 400.0) << ap.dump(2);

  const nlohmann::json* agent = fault(ap, "agent_killed");
  ASSERT_NE(agent, nullptr) << ap.dump(2);
  ASSERT_TRUE((*agent)["worst"].is_number()) << agent->dump(2);
  EXPECT_GT((*agent)["worst"].get<double>(), 0.0);
  EXPECT_LE((*agent)["worst"].get<double>(), 150.0 * cover::test::time_scale()) << agent->dump(2);
  const double loss_s = ap["offboard_loss_param"]["value_s"].get<double>();
  for (const char* name : {"heartbeat_loss", "bridge_killed"}) {
    const nlohmann::json* f = fault(ap, name);
    ASSERT_NE(f, nullptr) << name << ": " << ap.dump(2);
    ASSERT_TRUE((*f)["worst"].is_number()) << f->dump(2);
    // PX4's own failsafe, after its COM_OF_LOSS_T and not long after.
    EXPECT_GE((*f)["median"].get<double>(), loss_s - 0.05) << f->dump(2);
    EXPECT_LE((*f)["worst"].get<double>(), loss_s + 1.0 * cover::test::time_scale()) << f->dump(2);
  }
  const nlohmann::json* cut = fault(ap, "heartbeat_loss");
  ASSERT_NE(cut, nullptr);
  EXPECT_TRUE((*cut)["tries"][0]["bridge_link_lost_s"].is_number()) << cut->dump(2);
}

}  // namespace
