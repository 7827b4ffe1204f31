// Time across hosts (docs/time.md) with the real processes: the UAV agent measures its
// clock against the simulator's and the UGV agents', reports the largest offset in its
// status, holds a task while one exceeds time_sync.max_offset_ms (naming both hosts and
// the offset in the task's status) and flies it once that host's clock is right again.
// The "other host" is a UGV agent started with the test-only COVER_TEST_CLOCK_OFFSET_MS.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vocabulary/task.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "cover/wire/task.hpp"
#include "process_support.hpp"
#include "sim_system.hpp"

namespace {

using cover::test::bin;
using cover::test::SimSystem;
using namespace std::chrono_literals;

// This suite's of 140..148 (tests/time_sync takes 140..144).
constexpr int kDomain = 147;
constexpr int kManagerDomain = 148;

using cover::test::read_text;
using cover::test::scaled;
using cover::test::time_scale;
using cover::test::wait_until;

// UGV agent 1 of `system`, started again with its clock shifted by `offset_ms` ("": not).
void restart_ugv1(SimSystem& system, const std::string& offset_ms, const std::string& log) {
  auto& ugv = system.ugvs().at(1);
  const int code = ugv->terminate(scaled(10s), SIGINT);
  EXPECT_TRUE(code == 0 || code == 130) << code;  // 130: stopped while it waited for the world
  cover::process::SpawnOptions options = cover::test::quiet("cyclone", system.domain(), log);
  if (!offset_ms.empty()) options.extra_env.push_back("COVER_TEST_CLOCK_OFFSET_MS=" + offset_ms);
  ugv = std::make_unique<cover::process::ChildProcess>(
      std::vector<std::string>{bin("cover-ugv-agent"), "--id", "1", "--run-id", system.run_id()},
      options);
}

void hold_with_the_offset_named_then_fly() {
  SimSystem system(kDomain, "ts", {"--scenario", "scenario2", "--standing"});
  restart_ugv1(system, "50", system.log_name("ugv1_offset"));
  auto uav = system.spawn(
      {bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "2"}, "uav");

  cover::dds::ParticipantOptions options;
  options.domain_id = system.domain();
  cover::dds::Participant station(options);
  auto status = station.make_reader(cover::dds::topics::uav_status(0));
  auto task_status = station.make_reader(cover::dds::topics::task_status());
  auto requests = station.make_writer(cover::dds::topics::task_request());
  auto world = std::make_unique<cover::sim::SharedWorld>();
  ASSERT_TRUE(system.read_world(*world));
  const double start_z_m = world->uavs[0].state.position_m.z;  // on its deck
  auto latest_status = [&] {
    const auto s = status.latest();
    return s ? s->sample : cover::msg::UavStatus{};
  };

  // The agent reports the shifted UGV agent as its largest offset, ~+50 ms.
  ASSERT_TRUE(wait_until(
      [&] {
        const auto s = latest_status();
        return s.max_offset_peer.find("/cover-ugv-agent-1") != std::string::npos &&
               std::abs(s.max_clock_offset_ms - 50.0) <= 1.0;
      },
      30s))
      << "status reports " << latest_status().max_clock_offset_ms << " ms to '"
      << latest_status().max_offset_peer << "'";
  std::printf("[ measured ] UAV agent -> UGV agent 1 (+50 ms injected): %+.3f ms\n",
              latest_status().max_clock_offset_ms);
  const std::string peer = latest_status().max_offset_peer;

  // The task is held, with the reason.
  const cover::mission::Task task =
      cover::mission::load_task_file(std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml", 2);
  ASSERT_TRUE(requests.wait_for_readers(1, scaled(20s)));
  std::string held;
  auto next_send = std::chrono::steady_clock::now();
  ASSERT_TRUE(wait_until(
      [&] {
        if (std::chrono::steady_clock::now() >= next_send) {
          requests.write(cover::wire::to_msg(task, 0.0));  // re-sent: a volatile request
          next_send += 300ms;
        }
        const auto s = task_status.latest();
        if (!s || s->sample.task_id != task.task_id) return false;
        held = s->sample.message;
        return s->sample.state == cover::msg::TaskState::TASK_PENDING;
      },
      20s))
      << "last task status: " << held;
  EXPECT_NE(held.find("waiting for the clocks to agree: clock offset from "), std::string::npos)
      << held;
  const std::string head = "/cover-uav-agent-0 to " + peer + " is ";
  const std::size_t at = held.find(head);
  ASSERT_NE(at, std::string::npos) << held;
  EXPECT_NEAR(std::atof(held.c_str() + at + head.size()), 50.0, 1.0) << held;
  EXPECT_NE(held.find("limit 20 ms"), std::string::npos) << held;
  std::printf("[ held     ] %s\n", held.c_str());
  // Another task meanwhile is refused, naming the one that waits.
  cover::mission::Task other = task;
  other.task_id = "while-held";
  std::string refused;
  ASSERT_TRUE(wait_until(
      [&] {
        requests.write(cover::wire::to_msg(other, 0.0));
        const auto s = task_status.latest();
        if (!s || s->sample.task_id != other.task_id) return false;
        refused = s->sample.message;
        return s->sample.state == cover::msg::TaskState::TASK_REJECTED;
      },
      10s));
  EXPECT_NE(refused.find("busy: task 'scenario2' is waiting for the clocks to agree"),
            std::string::npos)
      << refused;
  // Still held a while later (the re-sent request included): nothing flies.
  requests.write(cover::wire::to_msg(task, 0.0));
  std::this_thread::sleep_for(scaled(500ms));  // a window in which nothing may happen: not a sync
  // Its status reports the held task as its own, pending: not an idle agent.
  EXPECT_EQ(latest_status().task_id, task.task_id);
  EXPECT_EQ(latest_status().task_state, cover::msg::TaskState::TASK_PENDING);
  ASSERT_TRUE(system.read_world(*world));
  EXPECT_LT(world->uavs[0].state.position_m.z, start_z_m + 0.05);

  // The same UGV agent with a right clock: the task starts and the UAV takes off.
  restart_ugv1(system, "", system.log_name("ugv1"));
  ASSERT_TRUE(wait_until(
      [&] {
        const auto s = task_status.latest();
        return s && s->sample.task_id == task.task_id &&
               s->sample.state == cover::msg::TaskState::TASK_RUNNING;
      },
      20s))
      << "last task status: " << task_status.latest()->sample.message;
  EXPECT_TRUE(system.wait_for_world(
      [&](const cover::sim::SharedWorld& w) {
        return w.uavs[0].state.position_m.z > start_z_m + 0.1;
      },
      20s));
  // Every peer now within a millisecond: same host, loopback.
  ASSERT_TRUE(wait_until([&] { return std::abs(latest_status().max_clock_offset_ms) < 1.0; }, 10s))
      << latest_status().max_clock_offset_ms << " ms to " << latest_status().max_offset_peer;
  std::printf("[ measured ] UAV agent's largest offset, no injection: %+.3f ms (%s)\n",
              latest_status().max_clock_offset_ms, latest_status().max_offset_peer.c_str());

  EXPECT_EQ(uav->terminate(scaled(10s), SIGINT), 0);
  system.stop(scaled(10s));
  // Only this run's segment is checked: other suites may run beside this one.
  EXPECT_FALSE(std::filesystem::exists(system.segment_path())) << system.segment_path();
}

TEST(TimeAcrossHosts, OffsetHoldsTheTaskWithTheReasonAndItFliesOnceGone) {
  hold_with_the_offset_named_then_fly();
}

// `cover ARGS --json` on `system`'s domain: its exit code and last JSON line.
std::pair<int, nlohmann::json> cover_cli(SimSystem& system, std::vector<std::string> args) {
  args.insert(args.begin(), COVER_CLI);
  args.insert(args.end(), {"--json", "--timeout", "20"});
  cover::process::SpawnOptions options =
      cover::test::quiet("cyclone", system.domain(), system.log_name("cover"));
  options.append_log = true;
  options.capture_stdout = true;
  cover::process::ChildProcess cli(args, options);
  std::string last;
  while (const auto line = cli.read_line(scaled(60s))) {
    if (!line->empty()) last = *line;
  }
  return {cli.wait(scaled(30s)).value_or(-1), nlohmann::json::parse(last, nullptr, false)};
}

nlohmann::json record_of(SimSystem& system, const std::string& task_id) {
  const auto [code, reply] = cover_cli(system, {"status", task_id});
  if (code != 0 || !reply.contains("tasks") || reply["tasks"].empty()) return {};
  return reply["tasks"][0];
}

// Through the task manager: the record shows why the agent holds the task, the manager
// does not fail it for not starting (the agent reports it as its pending task), and it
// flies once the clock is right; the manager logs its own offsets to the agents.
void task_manager_shows_the_hold() {
  SimSystem system(kManagerDomain, "tsm", {"--scenario", "scenario2", "--standing"});
  restart_ugv1(system, "50", system.log_name("ugv1_offset"));
  auto uav = system.spawn(
      {bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "2"}, "uav");
  // What is tested is the hold, not heartbeats: a loaded machine's 1 s stall must not fail
  // the task as "went silent" (the shipped heartbeat_timeout_s).
  const std::string config = cover::test::scratch_path(system.run_id() + "_manager.yaml");
  std::ofstream(config) << "task_manager:\n  heartbeat_timeout_s: 5.0\n";
  auto manager =
      system.spawn({bin("cover-task-manager"), "--db",
                    cover::test::scratch_path(system.run_id() + ".db"), "--config", config},
                   "manager");
  cover::dds::ParticipantOptions options;
  options.domain_id = system.domain();
  cover::dds::Participant station(options);
  auto status = station.make_reader(cover::dds::topics::uav_status(0));
  auto task_status = station.make_reader(cover::dds::topics::task_status());
  ASSERT_TRUE(wait_until(
      [&] {
        const auto s = status.latest();
        return s && std::abs(s->sample.max_clock_offset_ms - 50.0) <= 1.0;
      },
      30s));
  auto world = std::make_unique<cover::sim::SharedWorld>();
  ASSERT_TRUE(system.read_world(*world));
  const double start_z_m = world->uavs[0].state.position_m.z;

  const auto [submitted, reply] =
      cover_cli(system, {"submit", std::string(COVER_CONFIG_DIR) + "/tasks/scenario2.yaml"});
  ASSERT_EQ(submitted, 0) << reply.dump();
  nlohmann::json record;
  ASSERT_TRUE(wait_until(
      [&] {
        record = record_of(system, "scenario2");
        return record.value("reason", "").find("waiting for the clocks to agree") !=
               std::string::npos;
      },
      30s))
      << record.dump();
  std::printf("[ manager  ] %s: %s\n", record.value("state", "").c_str(),
              record.value("reason", "").c_str());
  // Past the manager's dispatch timeout (5 s): still held, not failed (the agent reports
  // the held task as its own), not flying.
  std::this_thread::sleep_for(scaled(6s));  // a window in which nothing may happen: not a sync
  record = record_of(system, "scenario2");
  EXPECT_NE(record.value("state", ""), "MANAGED_FAILED") << record.dump();
  EXPECT_NE(record.value("reason", "").find("waiting for the clocks to agree"), std::string::npos)
      << record.dump();
  ASSERT_TRUE(system.read_world(*world));
  EXPECT_LT(world->uavs[0].state.position_m.z, start_z_m + 0.05);

  // Released: the agent starts the task (its stage line replaces the reason). Whether the
  // flight then succeeds is the other tests' matter (and a loaded machine's).
  restart_ugv1(system, "", system.log_name("ugv1"));
  EXPECT_TRUE(wait_until(
      [&] {
        const auto s = task_status.latest();
        return s && s->sample.task_id == "scenario2" &&
               s->sample.state == cover::msg::TaskState::TASK_RUNNING &&
               s->sample.message.find("waiting") == std::string::npos;
      },
      20s));
  // The manager followed the agent all along: never "did not take the task".
  record = record_of(system, "scenario2");
  EXPECT_EQ(record.value("reason", "").find("did not take"), std::string::npos) << record.dump();

  EXPECT_EQ(manager->terminate(scaled(10s), SIGINT), 0);
  EXPECT_EQ(uav->terminate(scaled(10s), SIGINT), 0);
  system.stop(scaled(10s));
  const std::string log = read_text(system.log_path("manager"));
  EXPECT_NE(log.find("clock offset to "), std::string::npos) << "the manager logs its offsets";
  EXPECT_NE(log.find("/cover-ugv-agent-1 +"), std::string::npos) << log;
  EXPECT_NE(log.find("beyond the 20 ms limit"), std::string::npos) << log;
  EXPECT_FALSE(std::filesystem::exists(system.segment_path())) << system.segment_path();
}

TEST(TimeAcrossHosts, TheTaskManagerShowsWhyTheAgentHoldsTheTask) {
  task_manager_shows_the_hold();
}

// The process part of "host/process".
std::string process_of(const std::string& peer) {
  return peer.substr(peer.rfind('/') + 1);
}

// The clock exchange is addressed: a UAV agent asks the simulator, its autopilot's bridge
// and the UGVs of its task, not every UGV of the fleet; a UGV agent asks back only the UAV
// agents that ask it; a UGV nobody asks answers nobody. Four UGVs, one UAV flying between
// the first two; what goes over cover/time/* is read by a station on the domain.
void only_the_task_peers_are_asked() {
  SimSystem system(kDomain, "tsaddr",
                   {"--scenario", "fleet", "--uavs", "2", "--ugvs", "4", "--standing"});
  for (int k = 2; k < 4; ++k) {
    system.ugvs().push_back(system.spawn(
        {bin("cover-ugv-agent"), "--id", std::to_string(k), "--run-id", system.run_id()},
        "ugv" + std::to_string(k)));
  }
  cover::dds::ParticipantOptions options;
  options.domain_id = system.domain();
  cover::dds::Participant station(options);
  std::mutex mutex;
  std::map<std::string, std::set<std::string>> asked;     // requester -> responders named
  std::map<std::string, std::set<std::string>> answered;  // requester -> who answered
  auto requests = station.make_reader(cover::dds::topics::time_request(),
                                      [&](const cover::msg::TimeSyncRequest& r) {
                                        std::lock_guard<std::mutex> lock(mutex);
                                        auto& named = asked[process_of(r.requester)];
                                        named.insert(r.responders.begin(), r.responders.end());
                                        if (r.responders.empty()) named.insert("<everyone>");
                                      });
  // Each asker's replies on its own topic (cover/time/reply/<process>); the topic a reply
  // came on is kept with it: a reply on another asker's topic would reach that asker.
  std::map<std::string, std::set<std::string>> carried;  // topic's asker -> requesters on it
  std::vector<cover::dds::Reader<cover::msg::TimeSyncReply>> replies;
  const std::vector<std::string> askers{"cover-uav-agent-0", "cover-ugv-agent-0",
                                        "cover-ugv-agent-1", "cover-ugv-agent-2",
                                        "cover-ugv-agent-3"};
  for (const std::string& asker : askers) {
    replies.push_back(station.make_reader(
        cover::dds::topics::time_reply(asker), [&, asker](const cover::msg::TimeSyncReply& r) {
          std::lock_guard<std::mutex> lock(mutex);
          answered[process_of(r.requester)].insert(process_of(r.responder));
          carried[asker].insert(process_of(r.requester));
        }));
  }
  std::size_t shared = 0;  // the one reply topic every asker read before
  replies.push_back(station.make_reader(cover::dds::Topic<cover::msg::TimeSyncReply>::uncatalogued(
                                            "cover/time/reply", cover::dds::exchange_qos()),
                                        [&](const cover::msg::TimeSyncReply&) {
                                          std::lock_guard<std::mutex> lock(mutex);
                                          ++shared;
                                        }));
  auto uav =
      system.spawn({bin("cover-uav-agent"), "--id", "0", "--clock", "realtime", "--ugv-count", "4",
                    "--task", std::string(COVER_CONFIG_DIR) + "/tasks/fleet/uav0.yaml"},
                   "uav");
  const std::set<std::string> uav_peers{"cover-sim", "cover-mocap-relay*", "cover-fc-bridge-0",
                                        "cover-ugv-agent-0", "cover-ugv-agent-1"};
  const std::set<std::string> uav_answerers{"cover-sim", "cover-ugv-agent-0", "cover-ugv-agent-1"};
  auto copy = [&](auto& map, const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex);
    return map[key];
  };
  // Both of its UGVs ask it back once it asked them (their bursts answered).
  const bool settled = wait_until(
      [&] {
        return copy(answered, "cover-uav-agent-0") == uav_answerers &&
               copy(answered, "cover-ugv-agent-0") == std::set<std::string>{"cover-uav-agent-0"} &&
               copy(answered, "cover-ugv-agent-1") == std::set<std::string>{"cover-uav-agent-0"};
      },
      30s);
  // A window of requests at 1 Hz after the bursts: what is asked stays what was asked.
  std::this_thread::sleep_for(scaled(1500ms));  // observing that nothing else comes: not a sync
  EXPECT_TRUE(settled);
  EXPECT_EQ(copy(asked, "cover-uav-agent-0"), uav_peers);
  EXPECT_EQ(copy(answered, "cover-uav-agent-0"), uav_answerers);
  EXPECT_EQ(copy(asked, "cover-ugv-agent-0"), std::set<std::string>{"cover-uav-agent-0"});
  EXPECT_EQ(copy(asked, "cover-ugv-agent-1"), std::set<std::string>{"cover-uav-agent-0"});
  // UGVs 2 and 3: asked by no one, so they ask no one, and no one hears from them.
  for (const std::string k : {"cover-ugv-agent-2", "cover-ugv-agent-3"}) {
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_EQ(asked.count(k), 0u) << k;
    for (const auto& [requester, who] : answered) EXPECT_EQ(who.count(k), 0u) << requester;
    EXPECT_EQ(carried.count(k), 0u) << "replies on the topic of " << k << ", which asked no one";
  }
  {
    // Each asker's topic carries its own replies only, and none goes on a shared topic.
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [topic_asker, requesters] : carried) {
      EXPECT_EQ(requesters, std::set<std::string>{topic_asker}) << topic_asker;
    }
    EXPECT_EQ(shared, 0u) << "replies on cover/time/reply";
  }
  EXPECT_EQ(uav->terminate(scaled(10s), SIGINT), 0);
  // The UAV agent was delivered its own replies, none of another asker's (on one shared
  // topic it would have had its UGV agents' too: they asked it back all along).
  const std::string summary = "clock replies delivered to ";
  std::ifstream log(system.log_path("uav"));
  std::string line, found;
  while (std::getline(log, line)) {
    if (line.find(summary) != std::string::npos) found = line;
  }
  ASSERT_FALSE(found.empty()) << "no '" << summary << "' line in " << system.log_path("uav");
  std::printf("[ measured ] %s\n", found.c_str());
  const std::size_t count_at = found.find(": ", found.find(summary)) + 2;
  EXPECT_GT(std::atoll(found.c_str() + count_at), 0) << found;
  EXPECT_NE(found.find("(0 for another asker)"), std::string::npos) << found;
  system.stop(scaled(10s));
  EXPECT_FALSE(std::filesystem::exists(system.segment_path())) << system.segment_path();
}

TEST(TimeAcrossHosts, AUavAgentAsksOnlyItsTaskPeersAndTheyAskItBack) {
  only_the_task_peers_are_asked();
}

}  // namespace
