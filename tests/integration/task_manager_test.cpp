// The task manager with a ground station, as an operator uses them: real processes (the
// simulator's standing world, UGV and UAV agents, cover-task-manager, the `cover` CLI),
// real DDS, a real SQLite database.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/task_manager/task_store.hpp"

namespace {

using namespace std::chrono_literals;
using cover::process::ChildProcess;
namespace fs = std::filesystem;

std::string bin(const std::string& name) {
  return std::string(COVER_BIN_DIR) + "/" + name;
}

cover::process::SpawnOptions quiet(const std::string& vendor, int domain, const std::string& log) {
  cover::process::SpawnOptions options;
  options.extra_env = {"COVER_DDS=" + vendor, "COVER_DDS_DOMAIN=" + std::to_string(domain)};
  options.log_file = ::testing::TempDir() + log;
  return options;
}

// A standing system on its own domain: world, two UGV agents, one UAV agent (realtime, so
// that an operator's abort finds the task in flight), and a task manager on `db`.
class StandingSystem {
 public:
  StandingSystem(int domain, const std::string& manager_vendor)
      : domain_(domain), manager_vendor_(manager_vendor) {
    run_id_ = "tm_" + std::to_string(getpid()) + "_" + std::to_string(domain);
    db_ = ::testing::TempDir() + run_id_ + ".db";
    fs::remove(db_);
    children_.push_back(spawn({bin("cover-sim"), "--scenario", "scenario1", "--standing", "--clock",
                               "realtime", "--run-id", run_id_},
                              "fastdds", "sim"));
    for (const char* k : {"0", "1"}) {
      children_.push_back(spawn({bin("cover-ugv-agent"), "--id", k, "--run-id", run_id_}, "cyclone",
                                std::string("ugv") + k));
    }
    children_.push_back(
        spawn({bin("cover-uav-agent"), "--id", "0", "--ugv-count", "2", "--clock", "realtime"},
              "fastdds", "uav"));
    start_manager();
  }
  ~StandingSystem() {
    manager_.reset();
    for (auto it = children_.rbegin(); it != children_.rend(); ++it) (*it)->terminate(10s, SIGINT);
  }

  void start_manager() {
    manager_ = spawn({bin("cover-task-manager"), "--db", db_}, manager_vendor_, "manager");
  }
  void kill_manager() {
    kill(manager_->pid(), SIGKILL);
    manager_->wait(10s);
  }
  int stop_manager() { return manager_->terminate(10s, SIGINT); }

  // `cover ARGS --json` as a ground station on this domain: exit code and its last JSON line.
  std::pair<int, nlohmann::json> cover(std::vector<std::string> args,
                                       const std::string& vendor = "cyclone") {
    args.insert(args.begin(), COVER_CLI);
    args.insert(args.end(), {"--json", "--timeout", "20"});
    cover::process::SpawnOptions options = quiet(vendor, domain_, run_id_ + "_cover.log");
    options.capture_stdout = true;
    ChildProcess cli(args, options);
    std::string last;
    while (const auto line = cli.read_line(120s)) {
      if (!line->empty()) last = *line;
    }
    const int code = cli.wait(30s).value_or(-1);
    return {code, nlohmann::json::parse(last, nullptr, false)};
  }
  std::string task_file(const std::string& id, const std::string& extra = "",
                        const std::string& vmax = "1.5") const {
    const std::string path = ::testing::TempDir() + run_id_ + "_" + id + ".yaml";
    std::ofstream(path) << "task_id: " << id << "\nuav_id: 0\nprocesses:\n"
                        << "  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1.0], "
                           "transition_point_m: [0, 0, 1.0], final_point_m: [0, 0, 0.05], "
                           "final_action: land, vmax_m_s: "
                        << vmax << extra << "}\n";
    return path;
  }
  const std::string& db() const { return db_; }

 private:
  std::unique_ptr<ChildProcess> spawn(const std::vector<std::string>& argv,
                                      const std::string& vendor, const std::string& name) {
    return std::make_unique<ChildProcess>(argv,
                                          quiet(vendor, domain_, run_id_ + "_" + name + ".log"));
  }

  int domain_;
  std::string manager_vendor_;
  std::string run_id_;
  std::string db_;
  std::vector<std::unique_ptr<ChildProcess>> children_;
  std::unique_ptr<ChildProcess> manager_;
};

std::string state_of(const nlohmann::json& reply) {
  if (reply.contains("tasks") && !reply["tasks"].empty()) return reply["tasks"][0]["state"];
  if (reply.contains("state")) return reply["state"];  // a watch line is the record itself
  return "";
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

}  // namespace
