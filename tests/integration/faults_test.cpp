// Faults injected into real processes (docs/failsafes.md): a UAV agent, a UGV agent or the
// simulator killed, relative states withheld, motion-capture dropouts and IMU faults. Real
// processes, real DDS, the simulator's shared-memory world as ground truth. Realtime: in
// lockstep the simulator waits for a dead agent instead of flying on.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/task_manager/task_store.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "process_support.hpp"
#include "sim_system.hpp"

namespace {

using cover::test::bin;
using cover::test::quiet;
using cover::test::shm_entries;
using cover::test::SimSystem;
using cover::test::wait_until;

using namespace std::chrono_literals;
using cover::msg::FailsafeState;
using cover::process::ChildProcess;
using cover::sim::OffboardState;
using cover::sim::SharedWorld;
using Clock = std::chrono::steady_clock;

const std::string kTask = std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml";

// The UAV agent on Cyclone DDS (a killed Fast DDS process leaves its transport files in
// /dev/shm, dds-interop.md), flying the task from the start or waiting for one.
std::unique_ptr<ChildProcess> uav_agent(SimSystem& system, bool with_task) {
  std::vector<std::string> argv{bin("cover-uav-agent"), "--id", "0", "--clock", "realtime",
                                "--ugv-count",          "2"};
  if (with_task) argv.insert(argv.end(), {"--task", kTask});
  return system.spawn(argv, "uav");
}

// The UAV's touch-down: vertical speed just before contact, and whether it stayed level.
struct Touchdown {
  double vertical_speed_m_s = -1.0;
  double lowest_tilt_cos = 1.0;
  bool disarmed = false;
};

// Follows UAV 0 from now until it rests disarmed (`disarmed` tells how the test knows).
Touchdown watch_touchdown(SimSystem& system,
                          const std::function<bool(const SharedWorld&)>& disarmed,
                          std::chrono::milliseconds timeout) {
  Touchdown t;
  double last_vz = 0.0;
  t.disarmed = system.wait_for_world(
      [&](const SharedWorld& w) {
        const auto& uav = w.uavs[0];
        const auto q = uav.state.attitude.eigen();
        t.lowest_tilt_cos = std::min(t.lowest_tilt_cos, (q * Eigen::Vector3d::UnitZ()).z());
        if (!uav.contact.resting) {
          last_vz = uav.state.velocity_m_s.z;
        } else if (t.vertical_speed_m_s < 0.0) {
          t.vertical_speed_m_s = std::abs(last_vz);
        }
        return uav.contact.resting && disarmed(w);
      },
      timeout);
  return t;
}

// Every failsafe the UAV agent reported on its trace (100 Hz), with the step's stamp, and
// how far it has flown the current stage.
class TraceLog {
 public:
  explicit TraceLog(cover::dds::Participant& p)
      : reader_(p.make_reader(cover::dds::topics::uav_trace(0),
                              [this](const cover::msg::ControlTrace& t) {
                                std::lock_guard<std::mutex> lock(mutex_);
                                if (entries_.empty() || entries_.back().second != t.failsafe) {
                                  entries_.push_back({t.stamp_ns * 1e-9, t.failsafe});
                                }
                                if (t.stage != stage_) {
                                  stage_ = t.stage;
                                  stage_since_s_ = t.stamp_ns * 1e-9;
                                  stage_planned_ = false;
                                }
                                stage_planned_ = stage_planned_ || t.planned;
                                latest_s_ = t.stamp_ns * 1e-9;
                              })) {}
  std::vector<std::pair<double, FailsafeState>> changes() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_;
  }
  // How long the agent's steps have flown `stage` on that stage's own plan; < 0: it is not
  // the current stage, or its plan has not been adopted yet.
  double flown_on_plan_s(cover::msg::Stage stage) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stage_ == stage && stage_planned_ ? latest_s_ - stage_since_s_ : -1.0;
  }
  // The first change to `state` at or after `after_s`; < 0: none.
  double first(FailsafeState state, double after_s = 0.0) const {
    for (const auto& [t, s] : changes()) {
      if (s == state && t >= after_s) return t;
    }
    return -1.0;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::pair<double, FailsafeState>> entries_;
  cover::msg::Stage stage_ = cover::msg::Stage::STAGE_IDLE;
  double stage_since_s_ = 0.0;  // the step that entered stage_
  bool stage_planned_ = false;  // a plan of stage_ adopted since
  double latest_s_ = 0.0;       // the latest step
  cover::dds::Reader<cover::msg::ControlTrace> reader_;
};

cover::dds::ParticipantOptions on_domain(int domain) {
  cover::dds::ParticipantOptions options;
  options.vendor = cover::dds::Vendor::Cyclone;
  options.domain_id = domain;
  return options;
}

// Nothing of this run is left in /dev/shm (other sessions' entries come and go there).
void expect_nothing_left_in_shm(const std::string& run_id) {
  for (const std::string& name : shm_entries()) {
    EXPECT_EQ(name.find(run_id), std::string::npos) << "left in /dev/shm: " << name;
  }
}

// SIGKILL of the UAV agent in the transition stage: the flight controller's offboard-loss
// failsafe lands it, and the task manager fails the task within 2 s, saying why.
TEST(Faults, UavAgentKilledMidTransitionIsLandedAndItsTaskFails) {
  SimSystem system(181, "ft", {"--scenario", "scenario2", "--standing"});
  auto uav = uav_agent(system, false);
  const std::string db = cover::test::scratch_path(system.run_id() + ".db");
  std::remove(db.c_str());
  auto manager = system.spawn({bin("cover-task-manager"), "--db", db}, "manager");
  cover::dds::Participant probe(on_domain(system.domain()));
  TraceLog trace(probe);
  auto status = probe.make_reader(cover::dds::topics::uav_status(0));
  ASSERT_TRUE(status.wait_for_sample(30s)) << "UAV agent never heard";
  // Submitted once, as an operator does: a manager that has not heard the UAV yet holds
  // the submission until it has (restart_grace_s) rather than rejecting it.
  cover::process::SpawnOptions o = quiet("cyclone", system.domain(), system.log_name("cover"));
  ChildProcess cli({COVER_CLI, "submit", kTask, "--json", "--timeout", "20"}, o);
  ASSERT_EQ(cli.wait(60s), std::optional<int>(0));
  // Well into the transition: half a second of it flown on its plan, by the agent's steps.
  ASSERT_TRUE(wait_until(
      [&] { return trace.flown_on_plan_s(cover::msg::Stage::STAGE_TRANSITION) >= 0.5; }, 60s));
  kill(uav->pid(), SIGKILL);
  const auto killed = Clock::now();
  const double killed_unix_s =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  auto at_kill = std::make_unique<SharedWorld>();
  ASSERT_TRUE(system.wait_for_world(
      [&](const SharedWorld& w) {
        *at_kill = w;
        return true;
      },
      1s));
  double loss_s = -1.0;
  EXPECT_TRUE(system.wait_for_world(
      [&](const SharedWorld& w) {
        loss_s = w.time_s;
        return w.uavs[0].offboard == OffboardState::LossDescent;
      },
      3s));
  // Within offboard_timeout_s (0.5 s) + 50 ms of the last command (sent <= 10 ms before).
  EXPECT_LE(loss_s - at_kill->time_s, 0.55);
  const Touchdown touchdown = watch_touchdown(
      system,
      [](const SharedWorld& w) { return w.uavs[0].offboard == OffboardState::LossDisarmed; }, 30s);
  EXPECT_TRUE(touchdown.disarmed);
  EXPECT_GE(touchdown.vertical_speed_m_s, 0.0);
  EXPECT_LE(touchdown.vertical_speed_m_s, 1.0);
  EXPECT_GT(touchdown.lowest_tilt_cos, std::cos(0.5));
  // The manager's record: failed, because the agent went silent, within 2 s of its death.
  cover::task_manager::TaskStore store(db);
  double failed_after_s = -1.0;
  EXPECT_TRUE(wait_until(
      [&] {
        const auto record = store.find("scenario2");
        if (!record || record->state != cover::task_manager::TaskState::Failed) return false;
        failed_after_s = std::chrono::duration<double>(Clock::now() - killed).count();
        return true;
      },
      10s));
  const auto record = store.find("scenario2");
  ASSERT_TRUE(record);
  EXPECT_NE(record->reason.find("went silent"), std::string::npos) << record->reason;
  // The time of the history row says when the manager decided (the poll may lag).
  const auto history = store.history("scenario2");
  ASSERT_FALSE(history.empty());
  EXPECT_GT(failed_after_s, 0.0);
  EXPECT_LE(history.back().time_s - killed_unix_s, 2.0);
  EXPECT_EQ(manager->terminate(10s, SIGINT), 0);
}

// A UGV agent killed while its UGV is the reference frame: the UAV agent is on its ladder
// within 150 ms of the last IMU sample and lands, disarmed on contact.
TEST(Faults, UgvAgentKilledPutsTheUavInItsFailsafeAndItLands) {
  std::string run_id;
  {
    SimSystem system(182, "ft", {"--scenario", "scenario2"});
    run_id = system.run_id();
    cover::dds::Participant probe(on_domain(system.domain()));
    TraceLog trace(probe);
    double last_imu_s = 0.0;
    std::mutex imu_mutex;
    auto imu = probe.make_reader(cover::dds::topics::ugv_imu(0), [&](const cover::msg::UgvImu& m) {
      std::lock_guard<std::mutex> lock(imu_mutex);
      last_imu_s = std::max(last_imu_s, m.stamp_ns * 1e-9);
    });
    auto uav = uav_agent(system, true);
    // Climbing in G0's frame (the initial stage), above 0.8 m.
    ASSERT_TRUE(system.wait_for_world(
        [](const SharedWorld& w) {
          return w.uavs[0].offboard == OffboardState::Offboard &&
                 w.uavs[0].state.position_m.z > 0.8;
        },
        30s));
    kill(system.ugv(0).pid(), SIGKILL);
    system.ugv(0).wait(5s);
    ASSERT_TRUE(
        wait_until([&] { return trace.first(FailsafeState::FAILSAFE_EMERGENCY_HOVER) > 0; }, 5s));
    double last_imu;
    {
      std::lock_guard<std::mutex> lock(imu_mutex);
      last_imu = last_imu_s;
    }
    const double entered_s = trace.first(FailsafeState::FAILSAFE_IMU_HOLD, last_imu);
    ASSERT_GT(entered_s, 0.0);
    EXPECT_LE(entered_s - last_imu, 0.15);
    const Touchdown touchdown = watch_touchdown(
        system, [](const SharedWorld& w) { return w.uavs[0].command.thrust_m_s2 == 0.0; }, 30s);
    EXPECT_TRUE(touchdown.disarmed);
    EXPECT_LE(touchdown.vertical_speed_m_s, 1.0);
    EXPECT_GT(touchdown.lowest_tilt_cos, std::cos(0.5));
    EXPECT_GT(trace.first(FailsafeState::FAILSAFE_EMERGENCY_LANDED), 0.0);
    EXPECT_EQ(system.sim().wait(30s), std::optional<int>(1));  // the task failed
    EXPECT_EQ(uav->terminate(10s, SIGINT), 0);
    EXPECT_EQ(system.ugv(1).wait(10s), std::optional<int>(0));
    system.close_world();
  }
  expect_nothing_left_in_shm(run_id);
}

// Relative states withheld for 0.5 s mid-flight: emergency hover, then the stage resumes
// replanned and the task completes.
TEST(Faults, RelativeStatesBackAfterAGapResumeAndComplete) {
  SimSystem system(183, "ft", {"--scenario", "scenario2", "--relative-gap", "6.0", "0.5"});
  cover::dds::Participant probe(on_domain(system.domain()));
  TraceLog trace(probe);
  auto uav = uav_agent(system, true);
  EXPECT_EQ(system.sim().wait(120s), std::optional<int>(0));  // every task succeeded
  // On a loaded host a late sample can put it in the hover earlier too: the gap's is the
  // first one from its start.
  const double hover_s = trace.first(FailsafeState::FAILSAFE_EMERGENCY_HOVER, 6.0);
  ASSERT_GT(hover_s, 6.0);
  EXPECT_LE(hover_s - 6.0, 0.15);  // the last state was stamped just before 6.0 s
  EXPECT_GT(trace.first(FailsafeState::FAILSAFE_NONE, hover_s), hover_s);
  EXPECT_LT(trace.first(FailsafeState::FAILSAFE_EMERGENCY_LANDING), 0.0);
  EXPECT_EQ(uav->terminate(10s, SIGINT), 0);
}

// Relative states gone for good mid-flight: the agent hovers, then hands the blind landing
// to the flight controller (its own height sensing), which lands the UAV softly and level.
TEST(Faults, RelativeStatesLostForGoodAreLandedByTheFlightController) {
  SimSystem system(186, "ft", {"--scenario", "scenario2", "--relative-gap", "6.0", "1000"});
  cover::dds::Participant probe(on_domain(system.domain()));
  TraceLog trace(probe);
  auto uav = uav_agent(system, true);
  double descent_s = -1.0;
  ASSERT_TRUE(system.wait_for_world(
      [&](const SharedWorld& w) {
        descent_s = w.time_s;
        return w.uavs[0].offboard == OffboardState::LossDescent;
      },
      60s));
  // Hover from ~6.1 s for emergency_hover_s (1 s), then the landing's first step hands over:
  // the flight controller takes over then, not offboard_timeout_s (0.5 s) after silence.
  ASSERT_TRUE(wait_until(
      [&] { return trace.first(FailsafeState::FAILSAFE_EMERGENCY_LANDING, 6.0) > 0.0; }, 5s));
  const double landing_s = trace.first(FailsafeState::FAILSAFE_EMERGENCY_LANDING, 6.0);
  EXPECT_GT(landing_s, 6.9);
  EXPECT_NEAR(descent_s, landing_s, 0.2);
  const Touchdown touchdown = watch_touchdown(
      system,
      [](const SharedWorld& w) { return w.uavs[0].offboard == OffboardState::LossDisarmed; }, 30s);
  EXPECT_TRUE(touchdown.disarmed);
  EXPECT_GE(touchdown.vertical_speed_m_s, 0.0);
  EXPECT_LE(touchdown.vertical_speed_m_s, 1.0);
  EXPECT_GT(touchdown.lowest_tilt_cos, std::cos(0.5));
  EXPECT_EQ(system.sim().wait(60s), std::optional<int>(1));  // the task failed
  EXPECT_EQ(uav->terminate(10s, SIGINT), 0);
}

// Motion-capture dropouts (10 % of samples) and corrupted IMU samples: the mission succeeds.
TEST(Faults, MocapDropoutsAndImuFaultsStillSucceed) {
  const std::string scenario = cover::test::scratch_path("faults_dropouts.yaml");
  std::ifstream in(std::string(COVER_CONFIG_DIR) + "/scenarios/scenario2.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("../tasks/scenario2.yaml"), 23, kTask);
  text.replace(text.find("world: {seed: 2}"), 16,
               "world: {seed: 2}\n  relative_sensor: {dropout_probability: 0.1}\n"
               "  imu: {fault_probability: 0.01}");
  std::ofstream(scenario) << text;
  SimSystem system(184, "ft", {"--scenario", scenario});
  auto uav = uav_agent(system, true);
  EXPECT_EQ(system.sim().wait(120s), std::optional<int>(0));
  EXPECT_EQ(uav->terminate(10s, SIGINT), 0);
}

// The simulator killed mid-flight: the UGV agents see its world's writer dead and exit
// (the first removes the world it left), the UAV agent goes on its ladder and keeps waiting (SIGINT
// ends it cleanly); nothing is left in /dev/shm.
TEST(Faults, SimulatorKilledEveryAgentNoticesAndNothingIsLeft) {
  std::string run_id;
  {
    SimSystem system(185, "ft", {"--scenario", "scenario2"});
    run_id = system.run_id();
    cover::dds::Participant probe(on_domain(system.domain()));
    TraceLog trace(probe);
    auto uav = uav_agent(system, true);
    ASSERT_TRUE(system.wait_for_world(
        [](const SharedWorld& w) { return w.uavs[0].state.position_m.z > 0.8; }, 30s));
    system.close_world();
    kill(system.sim().pid(), SIGKILL);
    system.sim().wait(5s);
    // The first to see the dead writer exits 3 and removes the world; the other then finds
    // it closed and ends (0). Either way it stops publishing.
    std::vector<int> codes;
    for (int k = 0; k < 2; ++k) codes.push_back(system.ugv(k).wait(10s).value_or(-1));
    EXPECT_TRUE(std::count(codes.begin(), codes.end(), 3) >= 1);
    for (const int code : codes) EXPECT_TRUE(code == 0 || code == 3) << code;
    EXPECT_TRUE(
        wait_until([&] { return trace.first(FailsafeState::FAILSAFE_EMERGENCY_HOVER) > 0.0; }, 5s));
    EXPECT_FALSE(uav->wait(1s)) << "the UAV agent waits for a simulator";
    EXPECT_EQ(uav->terminate(10s, SIGINT), 0);
  }
  expect_nothing_left_in_shm(run_id);
}

}  // namespace
