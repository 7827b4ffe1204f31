// `foxglove: true` in a launch file and `cover-launch --foxglove`: the plan starts
// cover-foxglove-bridge before the run's processes (behind a recorder), respawned if it
// dies; a process of the file already named `foxglove` is refused; a non-boolean value is
// an error.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "cover/config/config_error.hpp"
#include "cover/launch/launch_plan.hpp"
#include "cover/launch/live_view.hpp"
#include "cover/launch/recording.hpp"
#include "launch_plan_support.hpp"

namespace cover::launch {
namespace {

using cover::launch::testing::options_in;
using cover::launch::testing::parse;

const char* const kLaunch = R"(launch:
  name: live
  kind: standing
  processes:
    - {name: sim, executable: cover-sim, ends_run: true}
)";

TEST(LaunchLiveView, FoxgloveKeyStartsTheBridgeBeforeTheRunBehindTheRecorder) {
  LaunchFile file = parse(std::string(kLaunch) + "  foxglove: true\n  record: true\n");
  EXPECT_TRUE(file.foxglove);
  const LaunchPlan plan = make_plan(file, options_in("/runs/l1"));
  ASSERT_EQ(plan.processes.size(), 3U);
  EXPECT_EQ(plan.processes[0].name, kRecorderName);
  EXPECT_EQ(plan.processes[1].name, kLiveViewName);
  EXPECT_EQ(plan.processes[1].executable, "cover-foxglove-bridge");
  EXPECT_TRUE(plan.processes[1].respawn.enabled);
  EXPECT_FALSE(plan.processes[1].ends_run);
  EXPECT_EQ(plan.processes[2].name, "sim");
}

TEST(LaunchLiveView, TheFlagAddsTheBridgeAndANameClashIsRefused) {
  EXPECT_EQ(make_plan(parse(kLaunch), options_in("/runs/l2")).processes.size(), 1U);
  LaunchOptions options = options_in("/runs/l2");
  options.foxglove = true;
  const LaunchPlan plan = make_plan(parse(kLaunch), options);
  ASSERT_EQ(plan.processes.size(), 2U);
  EXPECT_EQ(plan.processes[0].name, kLiveViewName);
  const std::string clash =
      std::string(kLaunch) + "    - {name: foxglove, executable: cover-sim}\n";
  EXPECT_THROW(make_plan(parse(clash), options), std::invalid_argument);
  EXPECT_THROW(parse(std::string(kLaunch) + "  foxglove: maybe\n"), config::ConfigError);
}

}  // namespace
}  // namespace cover::launch
