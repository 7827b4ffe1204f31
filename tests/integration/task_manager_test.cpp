// The task manager with a ground station, as an operator uses them: real processes (the
// simulator's standing world, UGV and UAV agents, cover-task-manager, the `cover` CLI),
// real DDS, a real SQLite database.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cover/clock/clock.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/task_manager/task_store.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vocabulary/task.hpp"
#include "cover/wire/task.hpp"
#include "manager_client.hpp"
#include "process_support.hpp"
#include "sim_system.hpp"

namespace {

using cover::test::bin;
using cover::test::quiet;
using cover::test::shm_entries;

using namespace std::chrono_literals;
using cover::process::ChildProcess;
namespace fs = std::filesystem;

// A standing system on its own domain: world, two UGV agents, one UAV agent (realtime, so
// that an operator's abort finds the task in flight), and a task manager on `db`.
class StandingSystem {
 public:
  // With `fleet_first` false no UAV agent is started (start_uav) and nothing is waited for.
  StandingSystem(int domain, const std::string& manager_vendor,
                 const std::string& clock = "realtime", int uavs = 1, bool fleet_first = true)
      : system_(domain, "tm",
                {"--scenario", uavs == 1 ? "scenario1" : "fleet_two_uavs", "--standing"}, clock),
        manager_vendor_(manager_vendor),
        clock_(clock) {
    db_ = cover::test::scratch_path(system_.run_id() + ".db");
    fs::remove(db_);
    if (fleet_first) {
      for (int u = 0; u < uavs; ++u) start_uav(u);
    }
    start_manager();
    if (fleet_first) wait_until_up(uavs);
  }
  void start_uav(int u) {
    uavs_.push_back(system_.spawn(
        {bin("cover-uav-agent"), "--id", std::to_string(u), "--ugv-count", "2", "--clock", clock_},
        "uav" + std::to_string(u), u == 0 ? "fastdds" : "cyclone"));
  }
  ~StandingSystem() {
    manager_.reset();
    for (auto it = uavs_.rbegin(); it != uavs_.rend(); ++it) (*it)->terminate(10s, SIGINT);
    system_.stop(10s);
  }

  // Until every UAV agent's heartbeat and both UGVs' IMU can be heard here (the manager,
  // listening as long, then hears them too): tasks are judged against the live fleet.
  void wait_until_up(int uavs) {
    cover::dds::ParticipantOptions options;
    options.vendor = cover::dds::Vendor::Cyclone;
    options.domain_id = system_.domain();
    cover::dds::Participant probe(options);
    for (int u = 0; u < uavs; ++u) {
      auto status =
          probe.make_reader(cover::dds::topics::uav_status(static_cast<std::uint32_t>(u)));
      ASSERT_TRUE(status.wait_for_sample(30s)) << "UAV " << u << " agent never heard";
    }
    for (std::uint32_t k = 0; k < 2; ++k) {
      auto imu = probe.make_reader(cover::dds::topics::ugv_imu(k));
      ASSERT_TRUE(imu.wait_for_sample(30s)) << "UGV " << k << " IMU never heard";
    }
  }

  void start_manager() {
    ++manager_starts_;
    manager_ = system_.spawn({bin("cover-task-manager"), "--db", db_},
                             "manager" + std::to_string(manager_starts_), manager_vendor_);
  }
  void kill_manager() {
    kill(manager_->pid(), SIGKILL);
    manager_->wait(10s);
  }
  int stop_manager() { return manager_->terminate(10s, SIGINT); }

  // `cover ARGS --json` as a ground station on this domain: exit code and its last JSON line.
  std::pair<int, nlohmann::json> cover(std::vector<std::string> args,
                                       const std::string& vendor = "cyclone") {
    return finish(*start_cover(std::move(args), vendor));
  }
  // The same in two halves: started, then its answer awaited.
  std::unique_ptr<ChildProcess> start_cover(std::vector<std::string> args,
                                            const std::string& vendor = "cyclone") {
    args.insert(args.begin(), COVER_CLI);
    args.insert(args.end(), {"--json", "--timeout", "20"});
    cover::process::SpawnOptions options =
        quiet(vendor, system_.domain(), system_.log_name("cover"));
    options.capture_stdout = true;
    return std::make_unique<ChildProcess>(args, options);
  }
  static std::pair<int, nlohmann::json> finish(ChildProcess& cli) {
    std::string last;
    while (const auto line = cli.read_line(120s)) {
      if (!line->empty()) last = *line;
    }
    const int code = cli.wait(30s).value_or(-1);
    return {code, nlohmann::json::parse(last, nullptr, false)};
  }
  int domain() const { return system_.domain(); }
  std::string task_file(const std::string& id, const std::string& extra = "",
                        const std::string& vmax = "1.5") const {
    const std::string path = cover::test::scratch_path(system_.run_id() + "_" + id + ".yaml");
    std::ofstream(path) << "task_id: " << id << "\nuav_id: 0\nprocesses:\n"
                        << "  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1.0], "
                           "transition_point_m: [0, 0, 1.0], final_point_m: [0, 0, 0.05], "
                           "final_action: land, vmax_m_s: "
                        << vmax << extra << "}\n";
    return path;
  }
  const std::string& db() const { return db_; }

 private:
  cover::test::SimSystem system_;  // first: its domain held until every child has stopped
  std::string manager_vendor_;
  std::string clock_;
  std::string db_;
  std::vector<std::unique_ptr<ChildProcess>> uavs_;
  std::unique_ptr<ChildProcess> manager_;
  int manager_starts_ = 0;
};

std::string state_of(const nlohmann::json& reply) {
  if (reply.contains("tasks") && !reply["tasks"].empty()) return reply["tasks"][0]["state"];
  if (reply.contains("state")) return reply["state"];  // a watch line is the record itself
  return "";
}

// "MANAGED_DISPATCHED" -> "dispatched", as the manager's messages name a state.
std::string state_word(const std::string& managed) {
  const std::string prefix = "MANAGED_";
  if (managed.rfind(prefix, 0) != 0) return "";
  std::string word = managed.substr(prefix.size());
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word;
}

TEST(TaskManager, SubmitWatchStatusListAndAbortFromAGroundStation) {
  StandingSystem system(171, "fastdds");
  const auto [submitted, reply] = system.cover({"submit", system.task_file("first")});
  ASSERT_EQ(submitted, 0) << reply.dump();
  EXPECT_TRUE(reply["ok"].get<bool>());
  // Queued behind it, then aborted before it flies: dropped from the queue.
  ASSERT_EQ(system.cover({"submit", system.task_file("queued")}).first, 0);
  const auto [aborted_queued, abort_reply] = system.cover({"abort", "queued"});
  EXPECT_EQ(aborted_queued, 0) << abort_reply.dump();
  EXPECT_EQ(state_of(abort_reply), "MANAGED_ABORTED") << abort_reply.dump();
  // Watched to its end: exit 0 only because it succeeded.
  const auto [watched, last_line] = system.cover({"watch", "first"}, "fastdds");
  EXPECT_EQ(watched, 0) << last_line.dump();
  EXPECT_EQ(state_of(last_line), "MANAGED_SUCCEEDED") << last_line.dump();
  const auto [status_code, status] = system.cover({"status", "first"});
  EXPECT_EQ(status_code, 0);
  EXPECT_EQ(state_of(status), "MANAGED_SUCCEEDED");
  // Aborted in flight: the agent holds, then lands; the record says aborted.
  ASSERT_EQ(system.cover({"submit", system.task_file("flying")}).first, 0);
  std::string state;
  for (int i = 0; i < 100 && state != "MANAGED_RUNNING"; ++i) {
    state = state_of(system.cover({"status", "flying"}).second);
  }
  ASSERT_EQ(state, "MANAGED_RUNNING");
  EXPECT_EQ(system.cover({"abort", "flying", "--reason", "operator"}).first, 0);
  const auto [flying_end, flying_last] = system.cover({"watch", "flying"});
  EXPECT_EQ(flying_end, 1) << "an aborted task is not a success";
  EXPECT_EQ(state_of(flying_last), "MANAGED_ABORTED") << flying_last.dump();
  const auto [listed, list] = system.cover({"list", "--all"});
  EXPECT_EQ(listed, 0);
  ASSERT_EQ(list["tasks"].size(), 3u) << list.dump();
  EXPECT_EQ(list["tasks"][0]["task_id"], "first");  // in submission order
  EXPECT_EQ(list["tasks"][1]["task_id"], "queued");
  EXPECT_EQ(list["tasks"][2]["task_id"], "flying");
  EXPECT_EQ(system.stop_manager(), 0);
}

TEST(TaskManager, BadSubmissionsAreRejectedWithAReasonAndTheManagerKeepsServing) {
  StandingSystem system(172, "cyclone");
  const auto [nan_code, nan_reply] =
      system.cover({"submit", system.task_file("nan", ", amax_m_s2: .nan")});
  EXPECT_NE(nan_code, 0);
  const auto [ugv_code, ugv_reply] =
      system.cover({"submit", [&] {
                      std::string f = system.task_file("far-ugv");
                      std::string text;
                      std::ifstream in(f);
                      text.assign(std::istreambuf_iterator<char>(in), {});
                      text.replace(text.find("to_ugv: 1"), 9, "to_ugv: 5");
                      std::ofstream(f) << text;
                      return f;
                    }()});
  EXPECT_EQ(ugv_code, 1) << ugv_reply.dump();
  EXPECT_EQ(state_of(ugv_reply), "MANAGED_REJECTED");
  EXPECT_NE(ugv_reply["message"].get<std::string>().find("UGV 5"), std::string::npos)
      << ugv_reply.dump();
  const auto [fast_code, fast_reply] =
      system.cover({"submit", system.task_file("too-fast", "", "9.0")});
  EXPECT_EQ(fast_code, 1) << fast_reply.dump();
  EXPECT_NE(fast_reply["message"].get<std::string>().find("vmax_m_s"), std::string::npos);
  EXPECT_EQ(system.cover({"status", "no-such-task"}).first, 1);
  // Still serving: a good task is accepted.
  EXPECT_EQ(system.cover({"submit", system.task_file("good")}).first, 0);
}

// A task submitted while its UAV agent is still starting (the agent not heard yet, the
// manager past its first heartbeat timeout of listening: discovery can take longer) waits
// for the agent instead of being rejected as not up.
TEST(TaskManager, ATaskSubmittedBeforeItsUavAgentIsHeardWaitsForIt) {
  StandingSystem system(178, "cyclone", "realtime", 1, /*fleet_first=*/false);
  // Every submission is held for the first heartbeat timeout, this one too: once it is
  // answered (rejected for its own fault) the manager has listened that long.
  const auto [fast_code, fast_reply] =
      system.cover({"submit", system.task_file("too-fast", "", "9.0")});
  ASSERT_EQ(fast_code, 1) << fast_reply.dump();
  const auto cli = system.start_cover({"submit", system.task_file("early")});
  system.start_uav(0);
  const auto [code, reply] = StandingSystem::finish(*cli);
  EXPECT_EQ(code, 0) << reply.dump();
  EXPECT_EQ(reply["message"], "queued for UAV 0") << reply.dump();
  EXPECT_EQ(system.stop_manager(), 0);
}

TEST(TaskManager, KilledWhileATaskRunsTheRestartedManagerRecordsItsTrueResult) {
  StandingSystem system(173, "fastdds");
  ASSERT_EQ(system.cover({"submit", system.task_file("survivor")}).first, 0);
  std::string state;
  for (int i = 0; i < 100 && state != "MANAGED_RUNNING"; ++i) {
    state = state_of(system.cover({"status", "survivor"}).second);
  }
  ASSERT_EQ(state, "MANAGED_RUNNING");
  system.kill_manager();  // SIGKILL mid-flight
  system.start_manager();
  const auto [watched, last_line] = system.cover({"watch", "survivor"});
  EXPECT_EQ(watched, 0) << last_line.dump();
  EXPECT_EQ(system.cover({"submit", system.task_file("survivor")}).second["tasks"].size(), 1u)
      << "a repeated id is the same task";
  EXPECT_EQ(system.stop_manager(), 0);
  // The database says so too, with the whole history.
  cover::task_manager::TaskStore store(system.db());
  const auto record = store.find("survivor");
  ASSERT_TRUE(record);
  EXPECT_EQ(record->state, cover::task_manager::TaskState::Succeeded) << record->reason;
  EXPECT_EQ(store.list(true).size(), 1u);
}

// A short task that ends hovering over the other UGV (no landing): the next one starts there.
cover::mission::Task hop(const std::string& id, int uav, int from, int to) {
  cover::mission::Task task;
  task.task_id = id;
  task.uav_id = uav;
  cover::mission::TransitionProcess p;
  p.from_ugv = from;
  p.to_ugv = to;
  p.initial_point_m = {0, 0, 1.0};
  p.transition_point_m = {0, 0, 1.0};
  p.final_point_m = {0, 0, 1.0};
  p.vmax_m_s = 1.5;
  task.processes.push_back(p);
  return task;
}

// Submits through the test's own ground station, re-trying while the manager restarts.
cover::msg::ManagerReply submit_until_answered(cover::cli::ManagerClient& client,
                                               const cover::mission::Task& task) {
  cover::msg::ManagerRequest r;
  r.kind = cover::msg::ManagerRequestKind::MANAGER_SUBMIT;
  r.task = cover::wire::to_msg(task, 0.0);
  for (int attempt = 0; attempt < 20; ++attempt) {
    try {
      return client.call(r);
    } catch (const cover::cli::ManagerUnreachable&) {
    }
  }
  throw std::runtime_error("no task manager for " + task.task_id);
}

int count_final(cover::cli::ManagerClient& client, int* succeeded) {
  cover::msg::ManagerRequest r;
  r.kind = cover::msg::ManagerRequestKind::MANAGER_QUERY;
  r.include_final = true;
  const cover::msg::ManagerReply reply = client.call(r);
  int final_count = 0;
  *succeeded = 0;
  for (const auto& t : reply.tasks) {
    using S = cover::msg::ManagedTaskState;
    if (t.state == S::MANAGED_SUCCEEDED) ++*succeeded;
    if (t.state == S::MANAGED_SUCCEEDED || t.state == S::MANAGED_FAILED ||
        t.state == S::MANAGED_ABORTED || t.state == S::MANAGED_REJECTED) {
      ++final_count;
    }
  }
  return final_count;
}

// 200 tasks queued for one UAV in lockstep; the manager SIGKILLed at 5 seeded moments and
// started again each time: every task recorded exactly once, dispatched once, in order.
TEST(TaskManager, TwoHundredTasksSurviveFiveKillsEachRecordedOnceInOrder) {
  constexpr int kTasks = 200;
  StandingSystem system(174, "fastdds", "lockstep");
  cover::dds::ParticipantOptions options;
  options.vendor = cover::dds::Vendor::Cyclone;
  options.domain_id = system.domain();
  cover::dds::Participant station(options);
  cover::cli::ManagerClient client(station, 5s);
  for (int i = 0; i < kTasks; ++i) {
    char id[16];
    std::snprintf(id, sizeof id, "hop%03d", i);
    const auto reply = submit_until_answered(client, hop(id, 0, i % 2, 1 - i % 2));
    ASSERT_TRUE(reply.ok) << id << ": " << reply.message;
  }
  std::mt19937 rng(2026);
  std::vector<int> kill_after;
  for (int i = 0; i < 5; ++i) kill_after.push_back(20 + static_cast<int>(rng() % 160));
  std::sort(kill_after.begin(), kill_after.end());
  const auto deadline = std::chrono::steady_clock::now() + 400s;
  int done = 0;
  int succeeded = 0;
  std::size_t kills = 0;
  while (done < kTasks && std::chrono::steady_clock::now() < deadline) {
    try {
      done = count_final(client, &succeeded);
    } catch (const cover::cli::ManagerUnreachable&) {
      continue;  // restarting
    }
    if (kills < kill_after.size() && done >= kill_after[kills]) {
      system.kill_manager();
      system.start_manager();
      ++kills;
    }
  }
  ASSERT_EQ(done, kTasks) << succeeded << " succeeded before the deadline";
  EXPECT_EQ(kills, kill_after.size());
  EXPECT_EQ(system.stop_manager(), 0);

  cover::task_manager::TaskStore store(system.db());
  const auto records = store.list(true);
  ASSERT_EQ(records.size(), static_cast<std::size_t>(kTasks));
  double last_dispatch_s = 0.0;
  for (int i = 0; i < kTasks; ++i) {
    const auto& r = records[static_cast<std::size_t>(i)];
    char id[16];
    std::snprintf(id, sizeof id, "hop%03d", i);
    EXPECT_EQ(r.task_id, id);  // submission order
    EXPECT_EQ(r.state, cover::task_manager::TaskState::Succeeded) << id << ": " << r.reason;
    int dispatched = 0;
    for (const auto& change : store.history(r.task_id)) {
      if (change.to != cover::task_manager::TaskState::Dispatched) continue;
      ++dispatched;
      EXPECT_GE(change.time_s, last_dispatch_s) << id << " dispatched out of order";
      last_dispatch_s = change.time_s;
    }
    EXPECT_EQ(dispatched, 1) << id;
  }
}

// Two UAVs, two queues, one manager: both fly at once.
TEST(TaskManager, TwoUavsAreServedAtOnceFromTwoQueues) {
  StandingSystem system(175, "cyclone", "lockstep", 2);
  cover::dds::ParticipantOptions options;
  options.domain_id = system.domain();
  cover::dds::Participant station(options);
  cover::cli::ManagerClient client(station, 5s);
  for (int i = 0; i < 3; ++i) {
    const auto a = submit_until_answered(client, hop("a" + std::to_string(i), 0, i % 2, 1 - i % 2));
    ASSERT_TRUE(a.ok) << a.message;
    const auto b = submit_until_answered(client, hop("b" + std::to_string(i), 1, 1 - i % 2, i % 2));
    ASSERT_TRUE(b.ok) << b.message;
  }
  int succeeded = 0;
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (count_final(client, &succeeded) < 6 && std::chrono::steady_clock::now() < deadline) {
  }
  EXPECT_EQ(succeeded, 6);
  cover::task_manager::TaskStore store(system.db());
  // Both queues were in flight together: b0 was dispatched before a0 ended.
  double a0_end = 0.0, b0_dispatch = 0.0;
  for (const auto& c : store.history("a0")) {
    if (c.to == cover::task_manager::TaskState::Succeeded) a0_end = c.time_s;
  }
  for (const auto& c : store.history("b0")) {
    if (c.to == cover::task_manager::TaskState::Dispatched) b0_dispatch = c.time_s;
  }
  EXPECT_GT(b0_dispatch, 0.0);
  EXPECT_LT(b0_dispatch, a0_end);
  EXPECT_EQ(system.stop_manager(), 0);
}

// Fuzzed submissions straight onto the wire (not through the CLI's file checks): every one
// gets an answer with a reason, nothing crashes the manager, and the good task at the end
// is still accepted.
TEST(TaskManager, FuzzedSubmissionsAreAnsweredAndTheManagerSurvives) {
  StandingSystem system(176, "fastdds", "lockstep");
  cover::dds::ParticipantOptions options;
  options.vendor = cover::dds::Vendor::Cyclone;
  options.domain_id = system.domain();
  cover::dds::Participant station(options);
  cover::cli::ManagerClient client(station, 2s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> any(-1e6, 1e6);
  const double specials[] = {std::nan(""), INFINITY, -INFINITY, 1e308, -0.0};
  int rejected = 0;
  int dropped = 0;
  for (int i = 0; i < 60; ++i) {
    cover::msg::TransitionTask task =
        cover::wire::to_msg(hop("fuzz" + std::to_string(i), 0, 0, 1), 0.0);
    auto& p = task.processes[0];
    switch (rng() % 8) {
      case 0:
        p.final_point_m.z = specials[rng() % 5];
        break;
      case 1:
        p.vmax_m_s = any(rng);
        break;
      case 2:
        p.to_ugv = static_cast<std::uint32_t>(rng());
        break;
      case 3:
        task.processes.clear();
        break;
      case 4:
        p.final_action = static_cast<cover::msg::FinalAction>(3 + rng() % 100);
        break;
      case 5:
        task.uav_id = 1000 + rng() % 1000;
        break;
      case 6:
        p.initial_point_m.x = any(rng);
        break;
      default:
        task.task_id = std::string(1 + rng() % 300, static_cast<char>(1 + rng() % 255));
        break;
    }
    cover::msg::ManagerRequest r;
    r.kind = cover::msg::ManagerRequestKind::MANAGER_SUBMIT;
    r.task = task;
    try {
      const cover::msg::ManagerReply reply = client.call(r);
      EXPECT_FALSE(reply.message.empty()) << "submission " << i;
      if (!reply.ok) ++rejected;
    } catch (const cover::cli::ManagerUnreachable&) {
      // A sample the receiving vendor cannot decode (an enum value out of range) is
      // dropped by DDS before the manager sees it: refused, unanswered.
      ++dropped;
    }
  }
  EXPECT_GE(rejected + dropped, 50);
  EXPECT_LE(dropped, 15);  // a few mutations (a long id, a far but legal point) may fly
  EXPECT_TRUE(submit_until_answered(client, hop("after-the-fuzz", 0, 0, 1)).ok);
  EXPECT_EQ(system.stop_manager(), 0);
}

// --- A task manager and a fleet played by the test: vehicles heard or not, as it says ---

using cover::test::scaled;
using cover::test::time_scale;

// The fleet as the manager hears it, published by the test at 20 Hz: UAV agents idle,
// UGVs' IMU, and where a "bridge" runs, the UAV's autopilot (FcState) as set.
class FakeFleet {
 public:
  FakeFleet(int domain, std::vector<std::uint32_t> uavs, std::vector<std::uint32_t> ugvs)
      : participant_([&] {
          cover::dds::ParticipantOptions options;
          options.vendor = cover::dds::Vendor::Cyclone;
          options.domain_id = domain;
          return options;
        }()) {
    for (const auto u : uavs) {
      uav_writers_.emplace(u, participant_.make_writer(cover::dds::topics::uav_status(u)));
    }
    for (const auto k : ugvs) add_ugv(k);
    thread_ = std::thread([this] { run(); });
  }
  ~FakeFleet() {
    stop_ = true;
    thread_.join();
  }
  void add_ugv(std::uint32_t k) {
    std::lock_guard<std::mutex> lock(mutex_);
    ugv_writers_.emplace(k, participant_.make_writer(cover::dds::topics::ugv_imu(k)));
  }
  // From now on UAV u's bridge reports `state` (uav_id and stamp set here).
  void set_autopilot(std::uint32_t u, cover::msg::FcState state) {
    std::lock_guard<std::mutex> lock(mutex_);
    state.uav_id = u;
    auto writer = fc_writers_.find(u);
    if (writer == fc_writers_.end()) {
      writer =
          fc_writers_.emplace(u, participant_.make_writer(cover::dds::topics::fc_state(u))).first;
    }
    autopilots_[u] = state;
  }
  cover::dds::Participant& participant() { return participant_; }

 private:
  void run() {
    while (!stop_) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const std::int64_t now_ns = cover::clock::system_ns();
        for (auto& [u, writer] : uav_writers_) {
          cover::msg::UavStatus status;
          status.uav_id = u;
          status.stamp_ns = now_ns;
          writer.write(status);
        }
        for (auto& [k, writer] : ugv_writers_) {
          cover::msg::UgvImu imu;
          imu.ugv_id = k;
          imu.stamp_ns = now_ns;
          imu.specific_force_m_s2.z = 9.81;
          writer.write(imu);
        }
        for (auto& [u, state] : autopilots_) {
          state.stamp_ns = now_ns;
          fc_writers_.at(u).write(state);
        }
      }
      std::this_thread::sleep_for(50ms);  // the publishing rate, not a synchronisation
    }
  }

  cover::dds::Participant participant_;
  std::mutex mutex_;
  std::map<std::uint32_t, cover::dds::Writer<cover::msg::UavStatus>> uav_writers_;
  std::map<std::uint32_t, cover::dds::Writer<cover::msg::UgvImu>> ugv_writers_;
  std::map<std::uint32_t, cover::dds::Writer<cover::msg::FcState>> fc_writers_;
  std::map<std::uint32_t, cover::msg::FcState> autopilots_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// cover-task-manager alone on a domain, with limits written by the test.
class LoneManager {
 public:
  LoneManager(int domain, const std::string& limits_yaml)
      : claim_(cover::test::claim_domain(domain)), domain_(domain) {
    const std::string config =
        cover::test::scratch_path("task_manager_" + std::to_string(domain) + ".yaml");
    std::ofstream(config) << "task_manager:\n" << limits_yaml;
    db_ = cover::test::scratch_path("tasks_" + std::to_string(domain) + ".db");
    manager_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{bin("cover-task-manager"), "--db", db_, "--config", config},
        quiet("fastdds", domain, "manager_" + std::to_string(domain) + ".log"));
  }
  ~LoneManager() { manager_->terminate(10s, SIGINT); }
  int stop() { return manager_->terminate(10s, SIGINT); }
  int domain() const { return domain_; }
  const std::string& db() const { return db_; }

  // `cover ARGS` on this domain: its exit code and stdout lines, each with the time since
  // the command started.
  struct Output {
    int code = -1;
    std::vector<std::pair<double, std::string>> lines;
    std::string text() const {
      std::string all;
      for (const auto& line : lines) all += line.second + "\n";
      return all;
    }
  };
  std::unique_ptr<ChildProcess> start_cover(std::vector<std::string> args) const {
    args.insert(args.begin(), COVER_CLI);
    auto options = quiet("cyclone", domain_, "cover_" + std::to_string(domain_) + ".log");
    options.capture_stdout = true;
    return std::make_unique<ChildProcess>(args, options);
  }
  // The next `count` lines of a started `cover` (all of them: count 0), then its end.
  static Output read(ChildProcess& cli, std::chrono::steady_clock::time_point started,
                     std::size_t count = 0) {
    Output output;
    while (count == 0 || output.lines.size() < count) {
      const auto line = cli.read_line(scaled(60s));
      if (!line) break;
      const double at_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      output.lines.emplace_back(at_s, *line);
    }
    if (count == 0) output.code = cli.wait(scaled(30s)).value_or(-1);
    return output;
  }
  Output cover(std::vector<std::string> args) const {
    const auto started = std::chrono::steady_clock::now();
    return read(*start_cover(std::move(args)), started);
  }

  std::string task_file(const std::string& id, int to_ugv) const {
    const std::string path = cover::test::scratch_path(id + ".yaml");
    std::ofstream(path) << "task_id: " << id << "\nuav_id: 0\nprocesses:\n"
                        << "  - {from_ugv: 0, to_ugv: " << to_ugv
                        << ", initial_point_m: [0, 0, 1.0], transition_point_m: [0, 0, 1.0], "
                           "final_point_m: [0, 0, 0.05], final_action: land, vmax_m_s: 1.5}\n";
    return path;
  }

 private:
  cover::dds::DomainClaim claim_;
  int domain_;
  std::string db_;
  std::unique_ptr<ChildProcess> manager_;
};

// Measured before: a task naming UGV 7 got its rejection after 4.1 s against the CLI's 5 s
// timeout, and on a busy machine the user saw only "the task manager did not answer". Now
// the manager says at once what it waits for, and the CLI waits for the decision.
TEST(TaskManager, ASubmissionNamingAnUnheardVehicleIsAnsweredAtOnceThenDecided) {
  // A grace of 6 s: the decision comes after the CLI's 3 s --timeout, as on a slow machine.
  LoneManager manager(211, "  restart_grace_s: 6.0\n");
  FakeFleet fleet(manager.domain(), {0}, {0, 1});
  const auto rejected =
      manager.cover({"submit", manager.task_file("to-ugv-7", 7), "--timeout", "3"});
  ASSERT_GE(rejected.lines.size(), 2u) << rejected.text();
  const std::string& waiting = rejected.lines.front().second;
  EXPECT_EQ(waiting.rfind("waiting", 0), 0u) << rejected.text();
  // The first answer is the manager's listening period or UGV 7; the CLI says which.
  EXPECT_NE(rejected.text().find("waiting for UGV 7 (not heard yet"), std::string::npos)
      << rejected.text();
  EXPECT_LT(rejected.lines.front().first, rejected.lines.back().first);
  EXPECT_EQ(rejected.code, 1) << rejected.text();
  EXPECT_NE(rejected.lines.back().second.find("UGV 7 is not publishing its IMU"), std::string::npos)
      << rejected.text();
  EXPECT_GT(rejected.lines.back().first, 3.0) << "decided after the CLI's own --timeout";

  // The same wait ends well when the vehicle comes up: accepted. (A new manager: the grace
  // counts from its start.)
  manager.stop();
  LoneManager again(211 + 1, "  restart_grace_s: 30.0\n");
  FakeFleet fleet_again(again.domain(), {0}, {0, 1});
  const auto started = std::chrono::steady_clock::now();
  const auto cli = again.start_cover(
      {"submit", again.task_file("to-ugv-7-later", 7), "--json", "--timeout", "3"});
  const auto first = LoneManager::read(*cli, started, 1);
  ASSERT_EQ(first.lines.size(), 1u) << "no interim answer";
  const auto interim = nlohmann::json::parse(first.lines.front().second, nullptr, false);
  EXPECT_EQ(interim.value("interim", false), true) << first.text();
  fleet_again.add_ugv(7);  // UGV 7's agent starts while the submission waits
  const auto accepted = LoneManager::read(*cli, started);
  EXPECT_EQ(accepted.code, 0) << first.text() << accepted.text();
  ASSERT_GE(accepted.lines.size(), 1u) << accepted.text();
  const auto final_reply = nlohmann::json::parse(accepted.lines.back().second, nullptr, false);
  EXPECT_EQ(final_reply.value("interim", true), false) << accepted.text();
  EXPECT_EQ(final_reply.value("message", ""), "queued for UAV 0") << accepted.text();
}

// Issue 31: a task naming UGV 7 was rejected; the same file corrected and submitted again
// was refused, "task 'hop' is already known: rejected". A submission rejected at once holds
// no id now; an accepted task holds its id: the same content again is answered as the
// first time, other content is refused naming the known task's state and what differs.
TEST(TaskManager, ARejectedSubmissionHoldsNoIdAndAReusedIdIsAnsweredByItsContent) {
  // A short grace: the submission naming UGV 7 waits for it that long, then is rejected.
  LoneManager manager(218, "  restart_grace_s: 2.0\n");
  FakeFleet fleet(manager.domain(), {0}, {0, 1});
  const auto last_reply = [](const LoneManager::Output& out) {
    return out.lines.empty() ? nlohmann::json()
                             : nlohmann::json::parse(out.lines.back().second, nullptr, false);
  };
  const auto rejected = manager.cover({"submit", manager.task_file("hop", 7), "--json"});
  ASSERT_EQ(rejected.code, 1) << rejected.text();
  const auto rejected_reply = last_reply(rejected);
  EXPECT_EQ(state_of(rejected_reply), "MANAGED_REJECTED") << rejected.text();
  EXPECT_NE(rejected_reply.value("message", "").find("UGV 7 is not publishing its IMU"),
            std::string::npos)
      << rejected.text();

  // The same file corrected (to_ugv 1), the same id: judged anew, accepted.
  const std::string corrected = manager.task_file("hop", 1);
  const auto accepted = manager.cover({"submit", corrected, "--json"});
  EXPECT_EQ(accepted.code, 0) << accepted.text();
  const auto accepted_reply = last_reply(accepted);
  EXPECT_EQ(accepted_reply.value("message", ""), "queued for UAV 0") << accepted.text();
  EXPECT_EQ(state_of(accepted_reply), "MANAGED_QUEUED") << accepted.text();

  // Again, the same content: answered as the first time (a station that lost the answer).
  const auto repeat = manager.cover({"submit", corrected, "--json"});
  EXPECT_EQ(repeat.code, 0) << repeat.text();
  EXPECT_EQ(last_reply(repeat).value("message", ""), "queued for UAV 0") << repeat.text();

  // Other content under the id: refused, naming the known task's state and the change.
  std::string text;
  {
    std::ifstream in(corrected);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.replace(text.find("vmax_m_s: 1.5"), 13, "vmax_m_s: 1.0");
  std::ofstream(corrected) << text;
  const auto other = manager.cover({"submit", corrected, "--json"});
  EXPECT_EQ(other.code, 1) << other.text();
  const auto other_reply = last_reply(other);
  const std::string message = other_reply.value("message", "");
  const std::string known_state = state_word(state_of(other_reply));
  EXPECT_FALSE(known_state.empty()) << other.text();
  EXPECT_EQ(message.rfind("task 'hop' is already known: " + known_state + " (", 0), 0u) << message;
  EXPECT_NE(message.find("processes[0].vmax_m_s 1.5 -> 1.0"), std::string::npos) << message;

  // The store, read beside the running manager: one task under the id, the rejected
  // submission kept whole, the id's history from the rejection on.
  cover::task_manager::TaskStore store(manager.db());
  ASSERT_EQ(store.list(true).size(), 1u);
  const auto record = store.find("hop");
  ASSERT_TRUE(record.has_value());
  EXPECT_TRUE(record->accepted);
  EXPECT_EQ(record->task.processes.at(0).to_ugv, 1);
  EXPECT_EQ(record->task.processes.at(0).vmax_m_s, 1.5);
  const auto kept = store.replaced_rejections("hop");
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].task.processes.at(0).to_ugv, 7);
  EXPECT_NE(kept[0].reason.find("UGV 7 is not publishing its IMU"), std::string::npos);
  const auto history = store.history("hop");
  ASSERT_GE(history.size(), 2u);
  EXPECT_EQ(history[0].to, cover::task_manager::TaskState::Rejected);
  EXPECT_EQ(history[1].from, cover::task_manager::TaskState::Rejected);
  EXPECT_EQ(history[1].to, cover::task_manager::TaskState::Queued);
  EXPECT_EQ(manager.stop(), 0);
}

// Where a flight-controller bridge reports the UAV's autopilot, a task waits in the queue
// until the autopilot is armed and in OFFBOARD, and `cover list` / `cover status` say why.
TEST(TaskManager, WithABridgeATaskWaitsForTheAutopilotSayingWhy) {
  LoneManager manager(213, "");
  FakeFleet fleet(manager.domain(), {0}, {0, 1});
  cover::msg::FcState posctl;
  posctl.link_ok = true;
  posctl.autopilot = cover::msg::FcAutopilot::FC_AUTOPILOT_PX4;
  posctl.armed = false;
  posctl.mode = cover::msg::FcMode::FC_MODE_MANUAL;
  posctl.mode_name = "POSCTL";
  fleet.set_autopilot(0, posctl);
  auto dispatched = fleet.participant().make_reader(cover::dds::topics::task_request());

  const auto empty = manager.cover({"list"});
  EXPECT_EQ(empty.code, 0) << empty.text();
  EXPECT_EQ(empty.text(), "no task queued or in flight (--all also lists the ended ones)\n");

  const auto submitted = manager.cover({"submit", manager.task_file("gated", 1)});
  ASSERT_EQ(submitted.code, 0) << submitted.text();
  const std::string why = "waiting for UAV 0: autopilot not in its offboard mode (mode POSCTL)";
  std::string listed;
  const auto deadline = std::chrono::steady_clock::now() + scaled(20s);
  while (listed.find(why) == std::string::npos && std::chrono::steady_clock::now() < deadline) {
    listed = manager.cover({"list"}).text();
  }
  EXPECT_NE(listed.find(why), std::string::npos) << listed;
  EXPECT_NE(listed.find("queued"), std::string::npos) << listed;
  const auto status = manager.cover({"status", "gated", "--json"});
  const auto record = nlohmann::json::parse(status.lines.back().second, nullptr, false);
  EXPECT_EQ(state_of(record), "MANAGED_QUEUED") << status.text();
  EXPECT_EQ(record["tasks"][0].value("reason", ""), why) << status.text();
  EXPECT_EQ(dispatched.received_count(), 0u) << "dispatched to an autopilot a pilot flies";

  cover::msg::FcState offboard = posctl;
  offboard.armed = true;
  offboard.mode = cover::msg::FcMode::FC_MODE_OFFBOARD;
  offboard.mode_name = "OFFBOARD";
  offboard.offboard_ready = true;
  fleet.set_autopilot(0, offboard);
  ASSERT_TRUE(dispatched.wait_for_sample(scaled(10s))) << "never dispatched once ready";
  EXPECT_EQ(dispatched.latest()->sample.task_id, "gated");
  const auto after = manager.cover({"status", "gated", "--json"});
  EXPECT_EQ(state_of(nlohmann::json::parse(after.lines.back().second, nullptr, false)),
            "MANAGED_DISPATCHED")
      << after.text();
}

// Issue 31: the standing system wrote cover_tasks.db into whatever folder it was started
// from (a repository's root). Without --db the manager keeps its tasks in the user's state
// directory ($XDG_STATE_HOME/cover), which it makes; with none it says so and exits 3.
TEST(TaskManager, WithoutDbItsTasksGoToTheUsersStateDirectory) {
  constexpr int kDomain = 179;
  const auto claim = cover::test::claim_domain(kDomain);
  const fs::path state = cover::test::scratch_path("state");
  auto options = quiet("fastdds", kDomain, "manager_default_db.log");
  options.extra_env.push_back("XDG_STATE_HOME=" + state.string());
  ChildProcess manager({bin("cover-task-manager")}, options);
  const fs::path db = state / "cover" / "tasks.db";
  const std::string log = cover::test::scratch_path("manager_default_db.log");
  EXPECT_TRUE(cover::test::wait_until(
      [&] {
        return cover::test::read_text(log).find("database " + db.string()) != std::string::npos;
      },
      20s))
      << cover::test::read_text(log);
  EXPECT_TRUE(fs::exists(db));
  EXPECT_EQ(manager.terminate(10s, SIGINT), 0);

  auto homeless = quiet("fastdds", kDomain, "manager_no_state.log");
  homeless.extra_env.insert(homeless.extra_env.end(), {"XDG_STATE_HOME=", "HOME=relative"});
  ChildProcess lost({bin("cover-task-manager")}, homeless);
  EXPECT_EQ(lost.wait(scaled(20s)), std::optional<int>(3));
  const std::string why = cover::test::read_text(cover::test::scratch_path("manager_no_state.log"));
  EXPECT_NE(why.find("no state directory"), std::string::npos) << why;
}

}  // namespace
