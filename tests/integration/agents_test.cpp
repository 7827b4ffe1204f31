// The agents and the simulator as a flight stack engineer pokes them: the offboard-loss
// failsafe when a UAV agent dies mid-flight, and tasks and aborts arriving over DDS.
// Real processes, real DDS, the simulator's real shared-memory world as ground truth.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/process/child_process.hpp"
#include "cover/shm/seqlock_reader.hpp"
#include "cover/sim/odometry_sensor.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vocabulary/task.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "cover/wire/task.hpp"
#include "process_support.hpp"
#include "sim_system.hpp"

namespace {

using cover::test::bin;
using cover::test::quiet;
using cover::test::shm_entries;
using cover::test::SimSystem;

using namespace std::chrono_literals;
using cover::process::ChildProcess;
using cover::sim::OffboardState;
using cover::sim::SharedWorld;

// Nothing of ours is left in /dev/shm (the tests of this binary run serially).
void expect_no_new_shm_entries(const std::set<std::string>& before) {
  for (const std::string& name : shm_entries()) {
    EXPECT_TRUE(before.count(name) > 0) << "left in /dev/shm: " << name;
  }
}

TEST(AgentsAndSimulator, OffboardLossLevelsDescendsAndDisarms) {
  const auto shm_before = shm_entries();
  SimSystem system(167, "it", {"--scenario", "scenario2"});
  // On Cyclone DDS: it is killed, and a killed Fast DDS process leaves its shared-memory
  // transport files behind (dds-interop.md).
  auto uav =
      system.spawn({bin("cover-uav-agent"), "--id", "0", "--task",
                    std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml", "--clock", "realtime"},
                   "uav");
  // In the air, climbing through 1 m above the ground, under the agent's command.
  ASSERT_TRUE(system.wait_for_world(
      [](const SharedWorld& w) {
        return w.uavs[0].offboard == OffboardState::Offboard && w.uavs[0].state.position_m.z > 1.0;
      },
      30s));
  kill(uav->pid(), SIGKILL);  // the agent dies: no more commands
  EXPECT_TRUE(system.wait_for_world(
      [](const SharedWorld& w) { return w.uavs[0].offboard == OffboardState::LossDescent; }, 3s));
  double lowest_tilt_cos = 1.0;
  EXPECT_TRUE(system.wait_for_world(
      [&](const SharedWorld& w) {
        const auto q = w.uavs[0].state.attitude.eigen();
        lowest_tilt_cos = std::min(lowest_tilt_cos, (q * Eigen::Vector3d::UnitZ()).z());
        return w.uavs[0].offboard == OffboardState::LossDisarmed;
      },
      20s));
  auto final_world = std::make_unique<SharedWorld>();
  ASSERT_TRUE(system.read_world(*final_world));
  EXPECT_TRUE(final_world->uavs[0].contact.resting);
  EXPECT_EQ(final_world->uavs[0].command.thrust_m_s2, 0.0);  // disarmed
  EXPECT_GT(lowest_tilt_cos, std::cos(0.5));                 // stayed near level
  // Interrupted, the simulator removes its world and the UGV agents end with it.
  EXPECT_EQ(system.sim().terminate(10s, SIGINT), 130);
  for (auto& ugv : system.ugvs()) EXPECT_EQ(ugv->wait(10s), std::optional<int>(0));
  EXPECT_NE(access(system.segment_path().c_str(), F_OK), 0);
  expect_no_new_shm_entries(shm_before);
}

// Collects the task statuses of one UAV.
class TaskStatusWatch {
 public:
  explicit TaskStatusWatch(cover::dds::Participant& participant)
      : reader_(participant.make_reader(cover::dds::topics::task_status())) {}
  // `send` (re-)sends the request the status answers, every 300 ms until it is seen: a
  // volatile request written just as the agent's reader matches can be missed.
  bool wait_for(const std::function<bool(const cover::msg::TaskStatus&)>& match,
                std::chrono::milliseconds timeout, const std::function<void()>& send = {}) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    auto next_send = std::chrono::steady_clock::now();
    std::uint64_t seen = 0;
    while (std::chrono::steady_clock::now() < deadline) {
      if (send && std::chrono::steady_clock::now() >= next_send) {
        send();
        next_send += 300ms;
      }
      const auto latest = reader_.latest();
      if (latest && match(latest->sample)) return true;
      if (reader_.wait_for_sample(50ms, seen)) seen = reader_.received_count();
    }
    return false;
  }

 private:
  cover::dds::Reader<cover::msg::TaskStatus> reader_;
};

// The CPU list ("1", "0-3") each thread of `pid` may run on, by thread id.
std::map<int, std::string> thread_cpus(int pid) {
  std::map<int, std::string> cpus;
  const std::string task_dir = "/proc/" + std::to_string(pid) + "/task";
  for (const auto& entry : std::filesystem::directory_iterator(task_dir)) {
    std::ifstream status(entry.path() / "status");
    for (std::string line; std::getline(status, line);) {
      if (line.rfind("Cpus_allowed_list:", 0) == 0) {
        cpus[std::stoi(entry.path().filename().string())] =
            line.substr(line.find_first_not_of(" \t", 18));
      }
    }
  }
  return cpus;
}

// The last CPU this process may use, when it may use more than one (else -1).
int last_of_several_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0 || CPU_COUNT(&set) < 2) return -1;
  int last = -1;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (CPU_ISSET(cpu, &set)) last = cpu;
  }
  return last;
}

// The whole flight of that test, in a scope of its own: its participants and processes
// are gone before the shared-memory check. The agent places its control thread alone on a
// CPU and waits for its states there after its rehearsal (the scenario launch files' way).
void fly_task_over_dds_validate_and_abort() {
  SimSystem system(168, "it", {"--scenario", "scenario2"});
  const int control_cpu = last_of_several_cpus();
  std::vector<std::string> agent{bin("cover-uav-agent"), "--id", "0", "--clock", "realtime",
                                 "--ugv-count",          "2"};
  if (control_cpu >= 0) {
    agent.insert(agent.end(), {"--control-cpu", std::to_string(control_cpu),
                               "--spin-after-rehearsal-s", "0.0005"});
  }
  auto uav = system.spawn(agent, "uav");
  cover::dds::ParticipantOptions options;
  options.domain_id = system.domain();
  cover::dds::Participant station(options);  // the ground station
  TaskStatusWatch statuses(station);
  auto requests = station.make_writer(cover::dds::topics::task_request());
  auto aborts = station.make_writer(cover::dds::topics::task_abort());
  auto uav_status = station.make_reader(cover::dds::topics::uav_status(0));
  auto reference = station.make_reader(cover::dds::topics::uav_reference(0));
  std::vector<cover::dds::Reader<cover::msg::UgvImu>> ugv_imu;
  for (std::uint32_t k = 0; k < 2; ++k) {
    ugv_imu.push_back(station.make_reader(cover::dds::topics::ugv_imu(k)));
  }
  ASSERT_TRUE(requests.wait_for_readers(1, 20s));
  ASSERT_TRUE(aborts.wait_for_readers(1, 20s));

  cover::mission::Task task =
      cover::mission::load_task_file(std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml", 2);
  cover::mission::Task bad = task;
  bad.task_id = "unknown-ugv";
  bad.processes[0].to_ugv = 5;
  EXPECT_TRUE(statuses.wait_for(
      [](const cover::msg::TaskStatus& s) {
        return s.task_id == "unknown-ugv" && s.state == cover::msg::TaskState::TASK_REJECTED &&
               s.message.find("to_ugv") != std::string::npos;
      },
      10s, [&] { requests.write(cover::wire::to_msg(bad, 0.0)); }));

  ASSERT_TRUE(statuses.wait_for(
      [](const cover::msg::TaskStatus& s) {
        return s.task_id == "scenario2" && s.state == cover::msg::TaskState::TASK_RUNNING;
      },
      10s, [&] { requests.write(cover::wire::to_msg(task, 0.0)); }));
  ASSERT_TRUE(system.wait_for_world(
      [](const SharedWorld& w) { return w.uavs[0].state.position_m.z > 1.0; }, 20s));
  // The ground station sees the flight: 10 Hz status and the stage's reference.
  ASSERT_TRUE(uav_status.wait_for_sample(5s));
  ASSERT_TRUE(reference.wait_for_sample(5s));
  const cover::msg::UavStatus status = uav_status.latest()->sample;
  EXPECT_EQ(status.task_id, "scenario2");
  EXPECT_EQ(status.task_state, cover::msg::TaskState::TASK_RUNNING);
  EXPECT_EQ(status.process_count, 1u);
  EXPECT_TRUE(status.armed);
  EXPECT_NE(status.stage, cover::msg::Stage::STAGE_IDLE);
  EXPECT_EQ(status.solver_status, cover::msg::SolverStatus::SOLVER_OK);
  EXPECT_GT(status.solve_time_us, 0.0);
  EXPECT_TRUE(std::isfinite(status.distance_to_stage_point_m));
  EXPECT_GT(reference.latest()->sample.positions_m.size(), 2u);
  if (control_cpu >= 0) {
    // The control thread (the main one) alone on its CPU; every other thread, the task's
    // planner started after the first placement among them, on the others.
    const auto cpus = thread_cpus(uav->pid());
    ASSERT_GT(cpus.size(), 3u);
    for (const auto& [tid, list] : cpus) {
      if (tid == uav->pid()) {
        EXPECT_EQ(list, std::to_string(control_cpu));
      } else {
        EXPECT_EQ(list.find(std::to_string(control_cpu)), std::string::npos)
            << "thread " << tid << " may run on " << list;
      }
    }
    std::ifstream log_file(system.log_path("uav"));
    const std::string log{std::istreambuf_iterator<char>(log_file), {}};
    EXPECT_NE(log.find("control thread on CPU " + std::to_string(control_cpu)), std::string::npos)
        << log;
  }
  // Each UGV agent publishes its wheel odometry speed (scenario 2's UGVs have it) beside
  // the IMU: close to the simulator's true forward speed (1 % scale error, 0.02 m/s noise,
  // a 32 ms low-pass, and a few ms between the sample and the world read here).
  auto truth = std::make_unique<SharedWorld>();
  for (std::uint32_t k = 0; k < 2; ++k) {
    ASSERT_TRUE(ugv_imu[k].wait_for_sample(5s));
    const cover::msg::UgvImu imu = ugv_imu[k].latest()->sample;
    ASSERT_TRUE(system.read_world(*truth));
    EXPECT_EQ(imu.speed_source, cover::msg::SpeedSource::SPEED_SOURCE_WHEEL_ODOMETRY) << k;
    EXPECT_NEAR(imu.speed_m_s, cover::sim::true_forward_speed_m_s(truth->ugvs[k]), 0.1) << k;
  }
  const auto before = uav_status.received_count();
  EXPECT_TRUE(uav_status.wait_for_sample(1s, before + 5));  // ~10 Hz: 5 more within 1 s
  cover::mission::Task second = task;
  second.task_id = "while-busy";
  EXPECT_TRUE(statuses.wait_for(
      [](const cover::msg::TaskStatus& s) {
        return s.task_id == "while-busy" && s.state == cover::msg::TaskState::TASK_REJECTED;
      },
      10s, [&] { requests.write(cover::wire::to_msg(second, 0.0)); }));

  cover::msg::TaskAbort abort;
  abort.task_id = "scenario2";
  abort.reason = "integration test";
  EXPECT_TRUE(statuses.wait_for(
      [](const cover::msg::TaskStatus& s) {
        return s.task_id == "scenario2" && s.state == cover::msg::TaskState::TASK_CANCELLED;
      },
      10s, [&] { aborts.write(abort); }));
  // Hold, then land where it was: on the ground or a deck, disarmed by the agent itself.
  EXPECT_TRUE(system.wait_for_world(
      [](const SharedWorld& w) {
        return w.uavs[0].contact.resting && w.uavs[0].command.thrust_m_s2 == 0.0 &&
               w.uavs[0].offboard == OffboardState::Offboard;
      },
      30s));
  // The aborted task has ended: the simulator ends the run (not a success) by itself.
  EXPECT_EQ(system.sim().wait(30s), std::optional<int>(1));
  EXPECT_EQ(uav->terminate(10s, SIGINT), 0);
  for (auto& ugv : system.ugvs()) EXPECT_EQ(ugv->wait(10s), std::optional<int>(0));
}

TEST(AgentsAndSimulator, TaskOverDdsIsValidatedRunsAndAborts) {
  const auto shm_before = shm_entries();
  fly_task_over_dds_validate_and_abort();
  expect_no_new_shm_entries(shm_before);  // the station's participant is gone too
}

// Lockstep waits for every UAV agent; one that stops answering (here: SIGSTOP) stalls the
// run, and the simulator ends it after stall_timeout_s naming the missing agent.
TEST(AgentsAndSimulator, LockstepStallNamesTheMissingAgent) {
  const std::string params = cover::test::scratch_path("stall_params.yaml");
  std::ofstream(params) << "sim_process:\n  stall_timeout_s: 1.0\n";
  SimSystem system(169, "it", {"--scenario", "scenario2", "--params", params}, "lockstep");
  auto uav = system.spawn({bin("cover-uav-agent"), "--id", "0", "--task",
                           std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml"},
                          "uav");
  ASSERT_TRUE(system.wait_for_world([](const SharedWorld& w) { return w.tick > 50; }, 30s));
  kill(uav->pid(), SIGSTOP);
  EXPECT_EQ(system.sim().wait(10s), std::optional<int>(4));
  std::ifstream log(system.log_path("sim"));
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("no command from UAV 0 (cover-uav-agent --id 0"), std::string::npos) << text;
  kill(uav->pid(), SIGCONT);
  EXPECT_EQ(uav->terminate(10s, SIGINT), 0);
  for (auto& ugv : system.ugvs()) EXPECT_EQ(ugv->wait(10s), std::optional<int>(0));
}

// A lockstep agent whose task's inputs never all connect (UGV 1's agent gone) waits up to
// connect_timeout_s (20 s) for their publishers, as in a stalled secure start; SIGINT ends
// that wait: the agent exits 0 within cover-launch's grace before SIGTERM (3 s), without
// reporting the missing publisher as a failure.
TEST(AgentsAndSimulator, AnAgentWaitingForItsInputsStopsOnSigint) {
  SimSystem system(169, "it", {"--scenario", "scenario2"}, "lockstep");
  system.ugvs()[1]->terminate(10s, SIGKILL);  // gone, whatever it had started
  auto uav = system.spawn({bin("cover-uav-agent"), "--id", "0", "--task",
                           std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml"},
                          "uav");
  const auto log = [&] {
    std::ifstream file(system.log_path("uav"));
    return std::string(std::istreambuf_iterator<char>(file), {});
  };
  ASSERT_TRUE(cover::test::wait_until(
      [&] { return log().find("for the task's inputs' publishers") != std::string::npos; }, 30s))
      << log();
  const auto asked = std::chrono::steady_clock::now();
  EXPECT_EQ(uav->terminate(cover::test::scaled(3s), SIGINT), 0) << log();
  std::printf(
      "[ measured ] SIGINT to exit while waiting for the inputs: %.0f ms\n",
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - asked).count());
  EXPECT_EQ(log().find("no publisher of"), std::string::npos) << log();
  EXPECT_EQ(system.sim().terminate(10s, SIGINT), 130);  // a run interrupted
  EXPECT_EQ(system.ugvs()[0]->terminate(10s, SIGINT), 0);
}

// The simulator publishes a lockstep tick again until it hears the answer; an answer can
// be lost (written before the agent's command writer matched the simulator's reader).
// Here the "simulator" is the test: a command reader that joins after tick 0 was answered
// must still get tick 0's command when the tick comes again, the same one (not a second
// step), and tick 1 is then stepped as usual.
TEST(AgentsAndSimulator, ALockstepTickPublishedAgainIsAnsweredAgain) {
  const auto claim = cover::test::claim_domain(177);
  cover::dds::ParticipantOptions options;
  options.domain_id = claim.domain();
  cover::dds::Participant simulator(options);
  auto clock = simulator.make_writer(cover::dds::topics::sim_clock());
  auto trace = simulator.make_reader(cover::dds::topics::uav_trace(0));
  ChildProcess uav({bin("cover-uav-agent"), "--id", "0", "--clock", "lockstep", "--ugv-count", "2"},
                   quiet("cyclone", claim.domain(), "answer_again_uav.log"));
  ASSERT_TRUE(clock.wait_for_readers(1, 30s));
  auto tick = [](std::uint64_t n) {
    cover::msg::SimClock t;
    t.tick = n;
    t.stamp_ns = static_cast<std::int64_t>(n) * 10'000'000;
    t.period_s = 0.01;
    t.mode = cover::msg::ClockMode::CLOCK_MODE_LOCKSTEP;
    t.imu_stamp_ns = -1;
    t.relative_stamp_ns = -1;
    return t;
  };
  // Publishes tick `n` every 20 ms (the simulator's republish period) until `answered`
  // holds (10 s at most, scaled), as the simulator does.
  auto publish_until = [&](std::uint64_t n, const std::function<bool()>& answered) {
    return cover::test::wait_until(
        [&] {
          if (answered()) return true;
          clock.write(tick(n));
          return false;
        },
        10s, 20ms);
  };
  auto stamped = [](const auto& reader, std::int64_t stamp_ns) {
    const auto last = reader.latest();
    return last && last->sample.stamp_ns == stamp_ns;
  };
  ASSERT_TRUE(publish_until(0, [&] { return stamped(trace, 0); })) << "tick 0 never answered";

  auto command = simulator.make_reader(cover::dds::topics::uav_command(0));
  ASSERT_TRUE(command.wait_for_writers(1, 30s));
  ASSERT_TRUE(publish_until(0, [&] { return stamped(command, 0); }))
      << "tick 0 published again was not answered again";
  EXPECT_EQ(command.latest()->sample.seq, 0u) << "tick 0 was stepped twice";

  ASSERT_TRUE(publish_until(1, [&] { return stamped(command, 10'000'000); }));
  EXPECT_EQ(command.latest()->sample.seq, 1u);
  EXPECT_EQ(uav.terminate(10s, SIGINT), 0);
}

}  // namespace
