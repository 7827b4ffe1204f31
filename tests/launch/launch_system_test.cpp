// config/launch/system.yaml as an operator runs it: the simulator's standing world, two UGV
// agents, a UAV agent and the task manager, as real processes on a DDS domain of their own.
// A hang-up of the launcher stops nothing; a UGV agent killed mid-flight is respawned while
// the others keep their pids, back before the UAV agent's ladder gives the flight up; every
// one-shot `cover fleet` lists the five processes, each described.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/test/process_alive.hpp"
#include "cover/wire/enums.hpp"
#include "launch_test_support.hpp"

namespace {

using namespace cover::launch::testing;
using cover::test::process_alive;
using namespace std::chrono_literals;

const std::vector<std::string> kProcesses{"sim", "ugv0", "ugv1", "uav0", "task_manager"};

class SystemLaunch : public LaunchProcess {
 protected:
  // system.yaml on `domain`, its task database in the scratch folder.
  void start_system(int domain, const std::string& clock = "lockstep") {
    claim_.emplace(cover::dds::DomainClaim::claim(domain, std::chrono::minutes(10)));
    launcher_ = start({std::string(COVER_SOURCE_DIR) + "/config/launch/system.yaml", "--run-dir",
                       run_dir_.string(), "--domain", std::to_string(domain), "--clock", clock,
                       "--var", "db=" + (dir_ / "tasks.db").string(), "--json"},
                      /*own_group=*/true);
    ASSERT_TRUE(fleet_heard()) << launch_log();
    // The launcher logs a start after the fork: on a loaded machine a process can be heard
    // on the domain before its start line is written.
    for (const auto& name : kProcesses) {
      ASSERT_TRUE(eventually([&] { return !started_pids(launch_log(), name).empty(); }, 30000ms))
          << name << " never started\n"
          << launch_log();
      const auto pids = started_pids(launch_log(), name);
      ASSERT_EQ(pids.size(), 1u) << name << " started more than once\n" << launch_log();
      pids_.push_back(pids.front());
    }
  }

  // Every agent heard on the domain, as the task manager must hear them.
  bool fleet_heard() {
    cover::dds::ParticipantOptions options;
    options.vendor = cover::dds::Vendor::Cyclone;
    options.domain_id = claim_->domain();
    cover::dds::Participant probe(options);
    auto uav = probe.make_reader(cover::dds::topics::uav_status(0));
    auto ugv0 = probe.make_reader(cover::dds::topics::ugv_imu(0));
    auto ugv1 = probe.make_reader(cover::dds::topics::ugv_imu(1));
    return uav.wait_for_sample(scaled(60s)) && ugv0.wait_for_sample(scaled(30s)) &&
           ugv1.wait_for_sample(scaled(30s));
  }

  // `cover ARGS --json` on the system's domain: exit code and its last JSON line.
  std::pair<int, nlohmann::json> cover(std::vector<std::string> args) {
    args.insert(args.begin(), COVER_CLI);
    args.insert(args.end(), {"--json", "--timeout", "20", "--dds", "cyclone"});
    cover::process::SpawnOptions options;
    // The domain by environment: the task commands share one set of DDS flags, and today
    // only the last subcommand's --domain is read.
    options.extra_env = {"COVER_DDS_DOMAIN=" + std::to_string(claim_->domain())};
    options.capture_stdout = true;
    options.log_file = (dir_ / "cover.stderr").string();
    cover::process::ChildProcess cli(args, options);
    std::string last;
    while (const auto line = cli.read_line(scaled(180s))) {
      if (!line->empty()) last = *line;
    }
    const int code = cli.wait(scaled(30s)).value_or(-1);
    return {code, nlohmann::json::parse(last, nullptr, false)};
  }

  static std::string state_of(const nlohmann::json& reply) {
    if (reply.is_object() && reply.contains("tasks") && !reply["tasks"].empty()) {
      return reply["tasks"][0]["state"];
    }
    return reply.is_object() && reply.contains("state") ? reply["state"] : "";
  }

  std::string hop_task(const std::string& id) const {
    const std::string path = (dir_ / (id + ".yaml")).string();
    std::ofstream(path) << "task_id: " << id << "\nuav_id: 0\nprocesses:\n"
                        << "  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1.0], "
                           "transition_point_m: [0, 0, 1.0], final_point_m: [0, 0, 0.05], "
                           "final_action: land, vmax_m_s: 1.5}\n";
    return path;
  }

  // SIGINT to the launcher: every process stops in order, nothing of the run is left.
  void stop_and_check() {
    kill(launcher_->pid(), SIGINT);
    const auto result = finish(*launcher_, 60000ms);
    EXPECT_EQ(result.exit_code, 130) << result.err;
    const auto report = nlohmann::json::parse(result.out, nullptr, false);
    ASSERT_TRUE(report.is_object()) << result.out;
    EXPECT_EQ(report.at("leftover_segments"), nlohmann::json::array())
        << "a process left its segment: the launcher removed it";
    for (const auto& process : report.at("processes")) {
      EXPECT_EQ(process.at("stopped_by"), "SIGINT") << process.dump();
    }
    expect_all_gone(report);
    const std::string run_id = report.at("run_id");
    for (const auto& entry : fs::directory_iterator("/dev/shm")) {
      EXPECT_EQ(entry.path().filename().string().find(run_id), std::string::npos) << entry.path();
    }
  }

  std::optional<cover::dds::DomainClaim> claim_;
  std::unique_ptr<cover::process::ChildProcess> launcher_;
  std::vector<int> pids_;  // in kProcesses' order
};

TEST_F(SystemLaunch, SighupToAStandingLaunchStopsNoProcess) {
  start_system(215);
  ASSERT_FALSE(HasFatalFailure());
  kill(launcher_->pid(), SIGHUP);
  // One at a time: a second SIGHUP sent while the first is pending is merged with it.
  ASSERT_TRUE(eventually([&] { return contains(launch_log(), "SIGHUP received (1)"); }))
      << launch_log();
  killpg(launcher_->pid(), SIGHUP);  // what a shell sends its jobs when it is hung up
  ASSERT_TRUE(eventually([&] { return contains(launch_log(), "SIGHUP received (2)"); }))
      << launch_log();
  // Still serving after the hang-up: the fleet is heard and the task manager answers.
  EXPECT_TRUE(fleet_heard());
  const auto [listed, list] = cover({"list"});
  EXPECT_EQ(listed, 0) << list.dump();
  EXPECT_TRUE(process_alive(launcher_->pid()));
  for (std::size_t i = 0; i < kProcesses.size(); ++i) {
    EXPECT_TRUE(process_alive(pids_[i])) << kProcesses[i];
    EXPECT_EQ(started_pids(launch_log(), kProcesses[i]).size(), 1u) << kProcesses[i];
  }
  stop_and_check();
}

// What a flight looks like from outside, on Cyclone DDS as the UAV agent runs in
// system.yaml: every change of the UAV agent's ladder (its 100 Hz control trace) with the
// frame and stage it flew in, and when a restarted UGV agent is first heard (its IMU
// sequence starts over).
class FlightWatch {
 public:
  using Clock = std::chrono::steady_clock;
  struct Change {
    Clock::time_point at;
    cover::msg::FailsafeState failsafe;
  };

  FlightWatch(int domain, std::uint32_t ugv) : participant_(options(domain)) {
    trace_ = participant_.make_reader(
        cover::dds::topics::uav_trace(0), [this](const cover::msg::ControlTrace& step) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (changes_.empty() || changes_.back().failsafe != step.failsafe) {
            changes_.push_back({Clock::now(), step.failsafe});
          }
          if (step.stage == cover::msg::Stage::STAGE_TRANSITION && !transition_since_) {
            transition_since_ = Clock::now();
          }
          reference_ugv_ = step.reference_ugv;
        });
    imu_ = participant_.make_reader(cover::dds::topics::ugv_imu(ugv),
                                    [this](const cover::msg::UgvImu& sample) {
                                      std::lock_guard<std::mutex> lock(mutex_);
                                      if (last_seq_ && sample.seq < *last_seq_ && !restart_heard_) {
                                        restart_heard_ = Clock::now();
                                      }
                                      last_seq_ = sample.seq;
                                    });
  }

  std::optional<Clock::time_point> transition_since() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return transition_since_;
  }
  std::uint32_t reference_ugv() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return reference_ugv_;
  }
  std::optional<Clock::time_point> restart_heard() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return restart_heard_;
  }
  // The ladder's states entered at or after `since`, in order.
  std::vector<cover::msg::FailsafeState> entered_since(Clock::time_point since) const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<cover::msg::FailsafeState> states;
    for (const auto& change : changes_) {
      if (change.at >= since) states.push_back(change.failsafe);
    }
    return states;
  }

 private:
  static cover::dds::ParticipantOptions options(int domain) {
    cover::dds::ParticipantOptions options;
    options.vendor = cover::dds::Vendor::Cyclone;
    options.domain_id = domain;
    return options;
  }

  cover::dds::Participant participant_;
  mutable std::mutex mutex_;
  std::vector<Change> changes_;
  std::optional<Clock::time_point> transition_since_;
  std::uint32_t reference_ugv_ = 0;
  std::optional<std::uint32_t> last_seq_;
  std::optional<Clock::time_point> restart_heard_;
  cover::dds::Reader<cover::msg::ControlTrace> trace_;
  cover::dds::Reader<cover::msg::UgvImu> imu_;
};

// " imu-hold none": the ladder's states as the agents log them.
std::string names(const std::vector<cover::msg::FailsafeState>& states) {
  std::string text;
  for (const auto state : states) {
    const auto failsafe = cover::wire::from_msg(state);
    text += std::string(" ") + (failsafe ? cover::mission::to_string(*failsafe) : "unknown");
  }
  return text;
}

// Realtime, so that the kill lands mid-flight: UGV 1's agent, whose IMU the UAV flies the
// transition on, is SIGKILLed half a second into the transition stage. The launcher restarts
// it after its 0.1 s respawn delay and the UAV agent hears it again inside the ladder's
// budget (IMU hold from 0.1 s, emergency hover from 0.2 s, landing from 1.2 s): the task
// completes. Before issue 31 the 1.0 s delay and a Fast DDS UAV agent's late discovery of
// a restarted Cyclone writer put the first sample past 1.2 s: landing, task failed.
TEST_F(SystemLaunch, AUgvAgentKilledMidFlightIsBackInTimeAndTheTaskCompletes) {
  start_system(214, "realtime");
  ASSERT_FALSE(HasFatalFailure());
  constexpr std::uint32_t kTarget = 1;  // the hop's to_ugv: the transition's frame
  FlightWatch watch(claim_->domain(), kTarget);
  const auto [submitted, reply] = cover({"submit", hop_task("through-a-kill")});
  ASSERT_EQ(submitted, 0) << reply.dump();
  ASSERT_TRUE(eventually(
      [&] {
        const auto since = watch.transition_since();
        return since && FlightWatch::Clock::now() - *since >= 500ms;
      },
      60000ms))
      << "the transition never started";
  ASSERT_EQ(watch.reference_ugv(), kTarget) << "the kill must hit the frame the UAV flies in";
  const int ugv1 = pids_[2];
  const auto killed_at = FlightWatch::Clock::now();
  kill(ugv1, SIGKILL);
  ASSERT_TRUE(eventually([&] { return started_pids(launch_log(), "ugv1").size() == 2; }, 30000ms))
      << launch_log();
  EXPECT_TRUE(
      contains(launch_log(), "ugv1 (pid " + std::to_string(ugv1) +
                                 ") died: killed by signal 9 (Killed); respawning in 0.1 s"))
      << launch_log();

  const auto [watched, last] = cover({"watch", "through-a-kill"});
  EXPECT_EQ(state_of(last), "MANAGED_SUCCEEDED") << last.dump();
  const auto heard = watch.restart_heard();
  ASSERT_TRUE(heard.has_value()) << "the restarted agent was never heard";
  const auto entered = watch.entered_since(killed_at);
  ASSERT_FALSE(entered.empty()) << "the kill did not reach the ladder";
  EXPECT_EQ(entered.front(), cover::msg::FailsafeState::FAILSAFE_IMU_HOLD) << names(entered);
  for (const auto state : entered) {
    EXPECT_NE(state, cover::msg::FailsafeState::FAILSAFE_EMERGENCY_LANDING) << names(entered);
  }
  std::cout << "[ MEASURED ] kill -> restarted ugv1 heard: "
            << std::chrono::duration<double, std::milli>(*heard - killed_at).count()
            << " ms; ladder after the kill:" << names(entered) << "\n";
  // The others were never restarted: same pids, alive.
  for (std::size_t i = 0; i < kProcesses.size(); ++i) {
    if (kProcesses[i] == "ugv1") continue;
    EXPECT_EQ(started_pids(launch_log(), kProcesses[i]), std::vector<int>{pids_[i]})
        << kProcesses[i];
    EXPECT_TRUE(process_alive(pids_[i])) << kProcesses[i];
  }
  stop_and_check();
}

// `cover fleet --json` as an operator runs it, once: its exit code, its document and how
// long it took.
struct FleetListing {
  int code = -1;
  nlohmann::json doc;
  double took_s = 0.0;
};

// What is wrong with one listing of system.yaml's five processes ("" when it is right):
// a row missing or extra, one stale, one not described ("still listening", or before
// issue 31 "heard in the clock exchange only" / "did not answer the query"), one not
// named by its own process in the clock exchange.
std::string wrong_in(const nlohmann::json& doc) {
  const std::map<std::string, std::string> expected{{"sim", "cover-sim"},
                                                    {"ugv-agent 0", "cover-ugv-agent-0"},
                                                    {"ugv-agent 1", "cover-ugv-agent-1"},
                                                    {"uav-agent 0", "cover-uav-agent-0"},
                                                    {"task-manager", "cover-task-manager"}};
  if (!doc.is_object() || !doc.contains("rows")) return "no document";
  std::string wrong;
  std::map<std::string, int> seen;
  for (const auto& row : doc["rows"]) {
    const std::string key =
        row.value("kind", "") + (row["id"].is_number() ? " " + row["id"].dump() : "");
    ++seen[key];
    const auto name = expected.find(key);
    if (name == expected.end()) {
      wrong += "extra row " + key + "; ";
      continue;
    }
    const std::string state = row.value("state", "");
    if (state.rfind("still listening", 0) == 0 || state == "heard in the clock exchange only" ||
        state == "did not answer the query") {
      wrong += key + ": " + state + "; ";
    }
    if (row.value("stale", true)) wrong += key + " stale; ";
    const auto& processes = row["processes"];
    const std::string process = processes.size() == 1 ? processes[0].get<std::string>() : "";
    if (process.substr(process.find('/') + 1) != name->second) {
      wrong += key + " named " + processes.dump() + "; ";
    }
  }
  for (const auto& [key, name] : expected) {
    if (seen[key] != 1) wrong += key + " listed " + std::to_string(seen[key]) + " times; ";
  }
  return wrong;
}

// Issue 31: on a standing realtime system about half of the one-shot listings were wrong
// (6 of 10 in one series: the simulator's row missing, the UAV agent "heard in the clock
// exchange only", the task manager "did not answer the query"), a Fast DDS listener being
// discovered by the Fast DDS processes at their next announcement, up to 3 s after it
// started, and the manager asked once, within the first 1.5 s. Ten listings in a row, on
// the CLI's default vendor: every one complete and right, within its bound.
TEST_F(SystemLaunch, EveryOneShotFleetListingOfAStandingSystemIsCompleteAndRight) {
  start_system(217, "realtime");
  ASSERT_FALSE(HasFatalFailure());
  // Up: the simulator ticks and the task manager answers (the agents: start_system).
  {
    cover::dds::ParticipantOptions options;
    options.vendor = cover::dds::Vendor::Cyclone;
    options.domain_id = claim_->domain();
    cover::dds::Participant probe(options);
    auto clock = probe.make_reader(cover::dds::topics::sim_clock());
    ASSERT_TRUE(clock.wait_for_sample(scaled(30s))) << "the simulator never ticked";
  }
  ASSERT_EQ(cover({"list"}).first, 0) << "the task manager never answered";

  const auto listing = [&] {
    cover::process::SpawnOptions options;
    options.extra_env = {"COVER_DDS_DOMAIN=" + std::to_string(claim_->domain())};
    options.capture_stdout = true;
    options.log_file = (dir_ / "fleet.stderr").string();
    const auto started = std::chrono::steady_clock::now();
    cover::process::ChildProcess cli({COVER_CLI, "fleet", "--json", "--dds", "fastdds"}, options);
    std::string last;
    while (const auto line = cli.read_line(scaled(60s))) {
      if (!line->empty()) last = *line;
    }
    FleetListing out;
    out.code = cli.wait(scaled(30s)).value_or(-1);
    out.took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    out.doc = nlohmann::json::parse(last, nullptr, false);
    return out;
  };
  constexpr int kListings = 10;
  // The first listing's bound: one Fast DDS announcement period (3 s) and the endpoints'
  // matching (0.5 s), then 2 s for what it discovered late to be described; a few of its
  // 50 ms steps of lateness on a loaded machine.
  const double bound_s = 3.0 + 0.5 + 2.0 + 0.2;
  int right = 0;
  std::string took;
  for (int i = 0; i < kListings; ++i) {
    SCOPED_TRACE("listing " + std::to_string(i + 1));
    const FleetListing run = listing();
    char line[64];
    std::snprintf(line, sizeof line, "%s%.2f s", took.empty() ? "" : ", ", run.took_s);
    took += line;
    EXPECT_EQ(run.code, 0);
    const std::string wrong = wrong_in(run.doc);
    EXPECT_EQ(wrong, "") << run.doc.dump(2);
    right += wrong.empty() ? 1 : 0;
    if (run.doc.is_object()) {
      EXPECT_LE(run.doc.value("listened_s", 1e9), bound_s * cover::test::time_scale());
    }
  }
  std::printf("[ MEASURED ] %d of %d listings right; each took %s\n", right, kListings,
              took.c_str());
  stop_and_check();
}

}  // namespace
