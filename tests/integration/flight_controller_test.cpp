// Scenario 2 flown through the flight-controller path a field vehicle takes: the UAV agent's
// commands go to cover-fc-bridge, which speaks MAVLink over UDP to the simulator's PX4 or
// ArduPilot autopilot (cover-sim --fc); the UGV agents read their IMUs from simulated UGV
// autopilots over MAVLink. Real processes through cover-launch, lockstep (the autopilot's
// failsafes and the injected faults run on simulated time, so they are deterministic).
// Domains 220..229; each test its own UDP ports (they run serially, but other suites do not).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cover/test/scratch_dir.hpp"
#include "launch_run.hpp"
#include "process_support.hpp"

namespace {

constexpr std::chrono::seconds kRunTimeout{300};
constexpr double kLandingTolerance_m = 0.05;
// The simulated vehicle's true hover thrust: g / max_thrust_m_s2 (config/sim/world_*.yaml).
constexpr double kTrueHoverThrust = 9.81 / 20.0;

// Four UDP ports a run needs (bridge, autopilot, UGV IMU base, UGV autopilot base), apart
// per domain and from the defaults (14540..14681) a developer's own launch may hold.
std::vector<std::string> port_vars(int domain) {
  const int base = 24000 + (domain - 220) * 16;
  return {"--var", "fc_port=" + std::to_string(base),
          "--var", "autopilot_port=" + std::to_string(base + 1),
          "--var", "ugv0_imu_port=" + std::to_string(base + 2),
          "--var", "ugv1_imu_port=" + std::to_string(base + 3),
          "--var", "ugv_autopilot_port=" + std::to_string(base + 4)};
}

cover::bench::LaunchOutcome fly(const std::string& autopilot, std::vector<std::string> flags,
                                int domain) {
  const auto claim = cover::test::claim_domain(domain);
  cover::bench::LaunchRequest request;
  request.launch_file = std::string(COVER_CONFIG_DIR) + "/launch/scenario2_" + autopilot + ".yaml";
  request.domain = domain;
  request.run_dir = cover::test::scratch_dir() / ("cover_fc_" + std::to_string(domain));
  request.flags = port_vars(domain);
  request.flags.insert(request.flags.end(), flags.begin(), flags.end());
  request.flags.push_back("--json");
  return cover::bench::run_launcher(request, "", kRunTimeout);
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

std::string text(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
}

struct HoverCase {
  const char* autopilot;
  double hover_error;  // relative error of the bridge's initial hover thrust
  int domain;
};

class ScenarioTwoThroughAutopilot : public ::testing::TestWithParam<HoverCase> {};

TEST_P(ScenarioTwoThroughAutopilot, SucceedsAndLandsWithinFiveCentimetres) {
  const HoverCase& c = GetParam();
  std::vector<std::string> flags;
  if (c.hover_error != 0.0) {
    flags = {"--var", "hover_thrust=" + std::to_string(kTrueHoverThrust * (1.0 + c.hover_error))};
  }
  const auto run = fly(c.autopilot, flags, c.domain);
  ASSERT_EQ(run.exit_code, 0) << run.stdout_text;
  EXPECT_TRUE(run.result.value("success", false)) << run.result.dump(2);
  const double landing_m = number(run.result, "landing_error_m");
  EXPECT_LE(landing_m, kLandingTolerance_m) << run.result.dump(2);
}

INSTANTIATE_TEST_SUITE_P(
    FlightController, ScenarioTwoThroughAutopilot,
    ::testing::Values(HoverCase{"px4", 0.0, 220}, HoverCase{"px4", 0.2, 221},
                      HoverCase{"px4", -0.2, 222}, HoverCase{"ardupilot", 0.0, 223},
                      HoverCase{"ardupilot", 0.2, 224}, HoverCase{"ardupilot", -0.2, 225}),
    [](const ::testing::TestParamInfo<HoverCase>& info) {
      const double e = info.param.hover_error;
      return std::string(info.param.autopilot) + (e == 0.0  ? "_hover_right"
                                                  : e > 0.0 ? "_hover_plus20"
                                                            : "_hover_minus20");
    });

// The safety pilot's RC switch mid-flight: the task fails at once with the reason, and the
// UAV is not lost (the autopilot holds it; the simulator ends the run on the failed task).
TEST(FlightController, PilotTakingOverFailsTheTaskWithTheReason) {
  const auto run = fly("px4", {"--var", "mode_switch=6:POSCTL"}, 226);
  EXPECT_EQ(run.exit_code, 3) << run.stdout_text;  // the simulator reports a failed task
  EXPECT_FALSE(run.result.value("success", true)) << run.result.dump(2);
  const std::string status = text(run.result, "status");
  EXPECT_NE(status.find("autopilot not in its offboard mode"), std::string::npos) << status;
  EXPECT_NE(status.find("POSCTL"), std::string::npos) << status;
}

TEST(FlightController, AutopilotHeartbeatLostFailsTheTaskWithTheReason) {
  const auto run = fly("ardupilot", {"--var", "heartbeat_stop=6"}, 227);
  EXPECT_EQ(run.exit_code, 3) << run.stdout_text;
  const std::string status = text(run.result, "status");
  EXPECT_NE(status.find("flight-controller link lost"), std::string::npos) << status;
}

}  // namespace
