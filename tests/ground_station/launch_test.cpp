// `ground_station: true` in a launch file and `cover-launch --ground-station`: the plan starts
// cover-ground-station before the run's processes, respawned if it dies; a process of the
// file already named `ground_station` is refused; a non-boolean value is an error; it gets the
// run's id and folder, and under DDS-Security the ground-station identity.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "cover/config/config_error.hpp"
#include "cover/launch/ground_station_view.hpp"
#include "cover/launch/launch_plan.hpp"
#include "cover/launch/security_identity.hpp"
#include "launch_plan_support.hpp"

namespace cover::launch {
namespace {

using cover::launch::testing::options_in;
using cover::launch::testing::parse;

const char* const kLaunch = R"(launch:
  name: station
  kind: standing
  processes:
    - {name: sim, executable: cover-sim, ends_run: true}
)";

TEST(LaunchGroundStation, KeyStartsTheStationBeforeTheRun) {
  LaunchFile file = parse(std::string(kLaunch) + "  ground_station: true\n");
  EXPECT_TRUE(file.ground_station);
  const LaunchPlan plan = make_plan(file, options_in("/runs/g1"));
  ASSERT_EQ(plan.processes.size(), 2U);
  EXPECT_EQ(plan.processes[0].name, kGroundStationName);
  EXPECT_EQ(plan.processes[0].executable, "cover-ground-station");
  EXPECT_TRUE(plan.processes[0].respawn.enabled);
  EXPECT_FALSE(plan.processes[0].ends_run);
  EXPECT_EQ(plan.processes[1].name, "sim");
  // The run's simulator world and folder, placeholders expanded.
  const auto& args = plan.processes[0].args;
  EXPECT_NE(std::find(args.begin(), args.end(), "--run-id=" + plan.run_id), args.end());
  EXPECT_NE(std::find(args.begin(), args.end(), "--record-dir=" + plan.run_dir), args.end());
}

// Under DDS-Security the station runs as the fleet's ground station, by its role.
TEST(LaunchGroundStation, SecureStationIsTheGroundStationIdentity) {
  EXPECT_EQ(launch_identity("ground_station", "cover-ground-station", {}, ""), "ground-station-0");
  EXPECT_EQ(launch_identity("ground_station", "/opt/bin/cover-ground-station", {"--port", "80"},
                            "ground-station-3"),
            "ground-station-3");
}

TEST(LaunchGroundStation, TheFlagAddsTheStationAndANameClashIsRefused) {
  EXPECT_EQ(make_plan(parse(kLaunch), options_in("/runs/g2")).processes.size(), 1U);
  LaunchOptions options = options_in("/runs/g2");
  options.ground_station = true;
  const LaunchPlan plan = make_plan(parse(kLaunch), options);
  ASSERT_EQ(plan.processes.size(), 2U);
  EXPECT_EQ(plan.processes[0].name, kGroundStationName);
  const std::string clash =
      std::string(kLaunch) + "    - {name: ground_station, executable: cover-sim}\n";
  EXPECT_THROW(make_plan(parse(clash), options), std::invalid_argument);
  EXPECT_THROW(parse(std::string(kLaunch) + "  ground_station: maybe\n"), config::ConfigError);
}

}  // namespace
}  // namespace cover::launch
