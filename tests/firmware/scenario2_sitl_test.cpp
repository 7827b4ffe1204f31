// Scenario 2 flown by the real firmware in COVER's world: config/launch/scenario2_px4_sitl.yaml
// and scenario2_ardupilot_sitl.yaml through cover-launch, lockstep and realtime. cover-sim is
// the firmware's physics (PX4's simulator_mavlink, ArduPilot's JSON backend); the UAV agent's
// commands reach the firmware through cover-fc-bridge over MAVLink. Every process is the real
// one; the firmware comes from COVER_PX4_SITL / COVER_ARDUPILOT_SITL (skipped without, failed
// with COVER_REQUIRE_FIRMWARE=1). Domains 212..215, SITL instances 6 and 7.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cover/dds/domain_claim.hpp"
#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/sitl_ports.hpp"
#include "cover/test/scratch_dir.hpp"
#include "launch_run.hpp"

namespace {

using cover::firmware::FirmwareLookup;

constexpr std::chrono::seconds kRunTimeout{420};
constexpr double kLandingTolerance_m = 0.05;

struct SitlCase {
  const char* firmware;  // "px4" / "ardupilot"
  const char* clock;
  int domain;
};

bool px4(const SitlCase& c) {
  return std::string(c.firmware) == "px4";
}

// The instance's ports, as the launch file's comment gives them.
std::vector<std::string> instance_vars(const SitlCase& c) {
  const int instance = px4(c) ? 6 : 7;
  const cover::Autopilot autopilot = px4(c) ? cover::Autopilot::Px4 : cover::Autopilot::ArduPilot;
  const int physics = cover::firmware::physics_port(autopilot, instance);
  return {"--var", "instance=" + std::to_string(instance),
          "--var", "physics_port=" + std::to_string(physics),
          "--var", "fc_port=" + std::to_string(cover::firmware::companion_port(instance))};
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

class ScenarioTwoOnRealFirmware : public ::testing::TestWithParam<SitlCase> {
 protected:
  void SetUp() override {
    const FirmwareLookup lookup = px4(GetParam()) ? cover::firmware::find_px4_sitl()
                                                  : cover::firmware::find_arducopter_sitl();
    if (lookup.build) return;
    if (cover::firmware::firmware_required()) {
      FAIL() << lookup.missing << " (COVER_REQUIRE_FIRMWARE=1)";
    }
    GTEST_SKIP() << lookup.missing;
  }
};

TEST_P(ScenarioTwoOnRealFirmware, SucceedsAndLandsOnTheMovingDeckWithinFiveCentimetres) {
  const SitlCase& c = GetParam();
  const auto claim = cover::dds::DomainClaim::claim(c.domain, std::chrono::minutes(10));
  cover::bench::LaunchRequest request;
  request.launch_file =
      std::string(COVER_CONFIG_DIR) + "/launch/scenario2_" + c.firmware + "_sitl.yaml";
  request.domain = c.domain;
  request.run_dir = cover::test::scratch_dir() / ("cover_sitl_" + std::to_string(c.domain));
  request.flags = instance_vars(c);
  request.flags.insert(request.flags.end(), {"--clock", c.clock, "--json"});
  const auto run = cover::bench::run_launcher(request, "", kRunTimeout);

  ASSERT_EQ(run.exit_code, 0) << run.stdout_text;
  const nlohmann::json& r = run.result;
  EXPECT_TRUE(r.value("success", false)) << r.dump(2);
  EXPECT_LE(number(r, "landing_error_m"), kLandingTolerance_m) << r.dump(2);
  // The firmware flew it: its physics link answered, and it armed.
  ASSERT_TRUE(r.contains("firmware")) << r.dump(2);
  const nlohmann::json& link = r["firmware"];
  EXPECT_TRUE(link.value("armed", false)) << link.dump();
  EXPECT_GT(link.value("answers", 0), 1000) << link.dump();
  if (std::string(c.clock) == "lockstep") EXPECT_EQ(link.value("answers_missed", -1), 0);
}

INSTANTIATE_TEST_SUITE_P(Sitl, ScenarioTwoOnRealFirmware,
                         ::testing::Values(SitlCase{"px4", "lockstep", 212},
                                           SitlCase{"px4", "realtime", 213},
                                           SitlCase{"ardupilot", "lockstep", 214},
                                           SitlCase{"ardupilot", "realtime", 215}),
                         [](const ::testing::TestParamInfo<SitlCase>& info) {
                           return std::string(info.param.firmware) + "_" + info.param.clock;
                         });

}  // namespace
