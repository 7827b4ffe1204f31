// `record: true` in a launch file and `cover-launch --record`: the plan starts `cover record`
// into the run folder first (so it is stopped last), never respawned, on the vendor --dds
// gives it; a process of the file already named `recorder` is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/launch/dds_override.hpp"
#include "cover/launch/launch_plan.hpp"
#include "cover/launch/recording.hpp"
#include "launch_plan_support.hpp"

namespace cover::launch {
namespace {

using cover::launch::testing::options_in;
using cover::launch::testing::parse;

const char* const kMission = R"(launch:
  name: recorded
  kind: standing
  processes:
    - {name: sim, executable: cover-sim, ends_run: true}
    - {name: uav0, executable: cover-uav-agent}
)";

TEST(LaunchRecord, RecordKeyStartsTheRecorderFirstIntoTheRunFolder) {
  LaunchFile file = parse(std::string(kMission) + "  record: true\n");
  EXPECT_TRUE(file.record);
  const LaunchPlan plan = make_plan(file, options_in("/runs/r1"));
  ASSERT_EQ(plan.processes.size(), 3U);
  const PlannedProcess& recorder = plan.processes.front();
  EXPECT_EQ(recorder.name, kRecorderName);
  EXPECT_EQ(recorder.args, (std::vector<std::string>{"record", "-o", "/runs/r1/recording.mcap"}));
  EXPECT_FALSE(recorder.respawn.enabled) << "a restart would truncate the recording";
  EXPECT_FALSE(recorder.ends_run);
  EXPECT_EQ(recorder.dds, "fastdds");
  EXPECT_NE(std::find(recorder.env.begin(), recorder.env.end(), "COVER_DDS_DOMAIN=7"),
            recorder.env.end());
  EXPECT_EQ(plan.processes[1].name, "sim");
}

TEST(LaunchRecord, TheFlagRecordsAndDdsGlobsReachTheRecorder) {
  const LaunchFile file = parse(kMission);
  EXPECT_FALSE(file.record);
  EXPECT_EQ(make_plan(file, options_in("/runs/r2")).processes.size(), 2U);
  LaunchOptions options = options_in("/runs/r2");
  options.record = true;
  options.dds_overrides.push_back(parse_dds_override("rec*=cyclone"));
  const LaunchPlan plan = make_plan(file, options);
  ASSERT_EQ(plan.processes.size(), 3U);
  EXPECT_EQ(plan.processes.front().name, "recorder");
  EXPECT_EQ(plan.processes.front().dds, "cyclone");
}

TEST(LaunchRecord, AProcessAlreadyNamedRecorderIsRefused) {
  const LaunchFile file = parse(R"(launch:
  name: clash
  record: true
  processes:
    - {name: recorder, executable: cover-sim, ends_run: true}
)");
  EXPECT_THROW(make_plan(file, options_in("/runs/r3")), std::invalid_argument);
  EXPECT_THROW(parse(std::string(kMission) + "  record: maybe\n"), config::ConfigError);
}

}  // namespace
}  // namespace cover::launch
