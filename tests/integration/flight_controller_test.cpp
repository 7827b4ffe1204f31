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

#include <signal.h>

#include <mutex>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/test/cpu_hog.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "launch_run.hpp"
#include "process_support.hpp"
#include "sim_system.hpp"

namespace {

constexpr std::chrono::seconds kRunTimeout{300};
constexpr double kLandingTolerance_m = 0.05;
// The simulated vehicle's true hover thrust: g * mass_true_kg / (mass_nominal_kg *
// max_thrust_m_s2) (config/sim/world_default.yaml: 1.05, 1.0, 20). The bridge's default
// (config/fc_bridge.yaml, 0.4905) is the nominal vehicle's: already 5 % off, as in the field.
constexpr double kTrueHoverThrust = 9.81 * 1.05 / 20.0;

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

// Lockstep through the bridge repeats bit for bit: the bridge takes each step's autopilot
// frames before the next tick's command, and the agent the bridge's state after that step
// (docs/flight-controller.md, "Lockstep"), however the processes are scheduled: a second
// run with every core busy lands at the same point, with the same events.
TEST(FlightController, LockstepThroughTheAutopilotRepeatsBitForBitUnderACpuHog) {
  constexpr int kDomain = 229;
  const auto quiet = fly("px4", {}, kDomain);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.stdout_text;
  // Every tick found what it waits for (a timeout would be logged, and lose the repeat).
  const auto run_dir = cover::test::scratch_dir() / ("cover_fc_" + std::to_string(kDomain));
  EXPECT_EQ(cover::test::read_text(run_dir / "fc0.log").find("repeat bit for bit"),
            std::string::npos);
  EXPECT_EQ(cover::test::read_text(run_dir / "uav0.log").find("the bridge's state after step"),
            std::string::npos);
  cover::bench::LaunchOutcome loaded;
  {
    const cover::test::CpuHog hog;
    loaded = fly("px4", {}, kDomain);
  }
  ASSERT_EQ(loaded.exit_code, 0) << loaded.stdout_text;
  for (const char* key : {"landing_error_m", "Lt", "tracking_error_m", "duration_s"}) {
    EXPECT_EQ(quiet.result.at(key), loaded.result.at(key)) << key;
  }
  EXPECT_EQ(quiet.result.at("fc").at("events"), loaded.result.at("fc").at("events"));
  EXPECT_EQ(quiet.result.at("fc").at("setpoints_accepted"),
            loaded.result.at("fc").at("setpoints_accepted"));
}

// The newest control step the UAV agent reported (its trace is written just before each
// command, stamped with the step's simulated time).
class LastStep {
 public:
  explicit LastStep(int domain) : participant_(options(domain)) {
    reader_ = participant_.make_reader(cover::dds::topics::uav_trace(0),
                                       [this](const cover::msg::ControlTrace& t) {
                                         std::lock_guard<std::mutex> lock(mutex_);
                                         stamp_s_ = t.stamp_ns * 1e-9;
                                       });
  }
  double stamp_s() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stamp_s_;
  }

 private:
  static cover::dds::ParticipantOptions options(int domain) {
    cover::dds::ParticipantOptions o;
    o.domain_id = domain;
    o.vendor = cover::dds::Vendor::Cyclone;
    return o;
  }
  cover::dds::Participant participant_;
  mutable std::mutex mutex_;
  double stamp_s_ = -1.0;
  cover::dds::Reader<cover::msg::ControlTrace> reader_;
};

// The agent killed in flight: the bridge switches the autopilot to its land mode within
// 150 ms of the last command it had (PX4's own offboard loss would wait 1 s), and the UAV
// lands. Realtime: in lockstep the simulator would wait for the dead agent.
TEST(FlightController, AgentKilledInFlightPutsTheAutopilotInLandModeWithin150ms) {
  constexpr int kDomain = 228;
  const std::vector<std::string> ports = port_vars(kDomain);  // --var k=v pairs
  const std::string fc_port = ports[1].substr(ports[1].find('=') + 1);
  const std::string autopilot_port = ports[3].substr(ports[3].find('=') + 1);
  cover::test::SimSystem system(kDomain, "fck",
                                {"--scenario", "scenario2", "--fc", "px4", "--fc-peer-port-base",
                                 fc_port, "--fc-bind-port-base", autopilot_port});
  LastStep last_step(kDomain);
  auto bridge =
      system.spawn({cover::test::bin("cover-fc-bridge"), "--id", "0", "--autopilot", "px4", "--url",
                    "udpin://127.0.0.1:" + fc_port, "--clock", "realtime", "--auto-arm"},
                   "bridge");
  auto agent = system.spawn(
      {cover::test::bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "2",
       "--fc-bridge", "--task", std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml"},
      "uav");
  // In the air, COVER flying it: well above the deck.
  ASSERT_TRUE(system.wait_for_world(
      [](const cover::sim::SharedWorld& w) {
        return w.uavs[0].offboard == cover::sim::OffboardState::Offboard &&
               !w.uavs[0].contact.resting && w.uavs[0].state.position_m.z > 1.2;
      },
      std::chrono::seconds(60)))
      << "never airborne under COVER; logs in " << cover::test::scratch_dir();
  kill(agent->pid(), SIGKILL);
  agent->wait(std::chrono::seconds(5));
  const double last_command_s = last_step.stamp_s();
  double land_s = -1.0;
  ASSERT_TRUE(system.wait_for_world(
      [&](const cover::sim::SharedWorld& w) {
        land_s = w.time_s;
        return w.uavs[0].offboard == cover::sim::OffboardState::LossDescent;
      },
      std::chrono::seconds(5)))
      << "the autopilot never left OFFBOARD";
  ASSERT_GT(last_command_s, 0.0);
  EXPECT_LE(land_s - last_command_s, 0.150)
      << "last command at " << last_command_s << " s, land mode seen at " << land_s << " s";
  // And it lands: at rest, motors off.
  EXPECT_TRUE(system.wait_for_world(
      [](const cover::sim::SharedWorld& w) {
        return w.uavs[0].contact.resting &&
               w.uavs[0].offboard == cover::sim::OffboardState::LossDisarmed;
      },
      std::chrono::seconds(60)));
  bridge->terminate(std::chrono::seconds(10), SIGINT);
  system.stop(std::chrono::seconds(10));
}

}  // namespace
