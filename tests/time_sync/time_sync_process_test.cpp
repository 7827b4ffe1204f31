// The clock exchange between two real processes on loopback: this test's OffsetMonitor
// and a time_sync_peer child answering with its (possibly shifted) clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "cover/dds/access_rules.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/time_sync/clock_responder.hpp"
#include "cover/time_sync/offset_monitor.hpp"

namespace cover::time_sync {
namespace {

using namespace std::chrono_literals;

using cover::test::scaled;
using cover::test::time_scale;
using cover::test::wait_until;

// Domains 140..144 (the integration test takes 147); the monitor and its peers share one.
struct Fixture {
  dds::DomainClaim claim = dds::DomainClaim::claim_any(140, 144);
  dds::ParticipantOptions options(dds::Vendor vendor) const {
    dds::ParticipantOptions o;
    o.vendor = vendor;
    o.domain_id = claim.domain();
    return o;
  }
  // `asks`: the peers it asks too (time_sync_peer's PEER... or --wait).
  std::unique_ptr<process::ChildProcess> peer(const std::string& vendor, const std::string& name,
                                              const std::string& offset_ms = "",
                                              const std::vector<std::string>& asks = {}) const {
    process::SpawnOptions spawn;
    spawn.capture_stdout = true;
    if (!offset_ms.empty()) spawn.extra_env.push_back("COVER_TEST_CLOCK_OFFSET_MS=" + offset_ms);
    std::vector<std::string> argv{COVER_TIME_SYNC_PEER, vendor, std::to_string(claim.domain()),
                                  name};
    argv.insert(argv.end(), asks.begin(), asks.end());
    auto child = std::make_unique<process::ChildProcess>(argv, spawn);
    // Its log lines come first on stdout (spdlog's default sink).
    const auto give_up = std::chrono::steady_clock::now() + scaled(10s);
    std::optional<std::string> line;
    std::string log;
    while (std::chrono::steady_clock::now() < give_up && line != "ready") {
      line = child->read_line(scaled(10s));
      if (!line) break;
      log += *line + "\n";
    }
    EXPECT_EQ(line.value_or("<nothing>"), "ready");
    // The test-only clock says so, loudly.
    EXPECT_EQ(log.find("TEST ONLY: COVER_TEST_CLOCK_OFFSET_MS=") != std::string::npos,
              !offset_ms.empty())
        << log;
    return child;
  }
};

MonitorOptions fast_monitor(std::vector<std::string> peers) {
  MonitorOptions m;
  m.process = "time-sync-test";
  m.peers = std::move(peers);
  m.params.burst_count = 16;
  m.params.burst_period_s = 0.05;
  m.params.request_period_s = 0.2;
  return m;
}

// Waits until the monitor holds a full window of `peer`'s samples (the estimate is then
// the best of several exchanges); its estimate.
std::optional<PeerOffset> settled(const OffsetMonitor& monitor, const std::string& process,
                                  std::chrono::milliseconds timeout) {
  const auto started = std::chrono::steady_clock::now();
  std::optional<PeerOffset> found;
  wait_until(
      [&] {
        for (const PeerOffset& p : monitor.offsets()) {
          if (p.peer.size() >= process.size() &&
              p.peer.compare(p.peer.size() - process.size(), process.size(), process) == 0) {
            found = p;
          }
        }
        // 16 burst exchanges take 0.8 s: by 1.5 s the window is the burst's best 8.
        return found && std::chrono::steady_clock::now() - started > 1500ms;
      },
      timeout, 20ms);
  return found;
}

void report(const char* what, const PeerOffset& p) {
  std::printf("[ measured ] %s: offset %+.3f ms, delay %.3f ms, uncertainty %.3f ms\n", what,
              ns_to_ms(p.estimate.offset_ns), ns_to_ms(p.estimate.delay_ns),
              ns_to_ms(p.estimate.uncertainty_ns));
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// DDS-Security: who asks and who answers, least privilege.
TEST(TimeSyncAccess, AgentsAndTheManagerAskSimAgentsAndBridgesAnswer) {
  using dds::Role;
  const std::string request = dds::topics::time_request().name();
  const std::string any_reply = "cover/time/reply/*";  // every asker's (fnmatch)
  const dds::Fleet fleet{2, 1, 1};
  auto access = [&](Role role) { return dds::topic_access({role, 0}, fleet); };
  auto own_reply = [&](Role role) {
    return dds::topics::time_reply("cover-" + dds::identity_name({role, 0})).name();
  };
  for (const Role asker : {Role::UavAgent, Role::UgvAgent, Role::TaskManager}) {
    EXPECT_TRUE(has(access(asker).publish, request)) << static_cast<int>(asker);
    EXPECT_TRUE(has(access(asker).subscribe, own_reply(asker))) << static_cast<int>(asker);
    EXPECT_FALSE(has(access(asker).subscribe, any_reply)) << static_cast<int>(asker);
  }
  EXPECT_FALSE(has(access(Role::UavAgent).subscribe, own_reply(Role::TaskManager)));
  for (const Role answerer : {Role::Sim, Role::UgvAgent, Role::UavAgent, Role::FcBridge}) {
    EXPECT_TRUE(has(access(answerer).subscribe, request)) << static_cast<int>(answerer);
    EXPECT_TRUE(has(access(answerer).publish, any_reply)) << static_cast<int>(answerer);
  }
  EXPECT_FALSE(has(access(Role::TaskManager).publish, any_reply));
  EXPECT_FALSE(has(access(Role::Sim).publish, request));
  EXPECT_FALSE(has(access(Role::FcBridge).publish, request));
  // A ground station may watch the exchange, not take part in it.
  EXPECT_TRUE(has(access(Role::GroundStation).subscribe, any_reply));
  EXPECT_FALSE(has(access(Role::GroundStation).publish, request));
  EXPECT_FALSE(has(access(Role::GroundStation).publish, any_reply));
}

class BetweenVendors : public ::testing::TestWithParam<std::pair<dds::Vendor, std::string>> {};

TEST_P(BetweenVendors, SameHostClocksAgreeWithinAMillisecond) {
  Fixture f;
  dds::Participant participant(f.options(GetParam().first));
  OffsetMonitor monitor(participant, fast_monitor({"cover-ugv-agent-*"}));
  auto child = f.peer(GetParam().second, "cover-ugv-agent-3");
  const auto p = settled(monitor, "/cover-ugv-agent-3", 20s);
  ASSERT_TRUE(p) << "no answer from the peer";
  report("same host", *p);
  EXPECT_LE(std::abs(ns_to_ms(p->estimate.offset_ns)), 1.0);
  EXPECT_LE(ns_to_ms(p->estimate.uncertainty_ns), 1.0);
  EXPECT_FALSE(monitor.limit_reason());
  EXPECT_EQ(monitor.refused_replies(), 0u);
}

INSTANTIATE_TEST_SUITE_P(
    TimeSync, BetweenVendors,
    ::testing::Values(std::make_pair(dds::Vendor::FastDds, std::string("fastdds")),
                      std::make_pair(dds::Vendor::Cyclone, std::string("cyclone")),
                      std::make_pair(dds::Vendor::FastDds, std::string("cyclone"))));

TEST(TimeSyncProcess, InjectedOffsetIsMeasuredNamedAndGoneAfterARestart) {
  Fixture f;
  dds::Participant participant(f.options(dds::Vendor::FastDds));
  OffsetMonitor monitor(participant, fast_monitor({"cover-sim", "cover-ugv-agent-*"}));
  auto good = f.peer("fastdds", "cover-sim");
  auto shifted = f.peer("fastdds", "cover-ugv-agent-1", "50");
  auto other = f.peer("fastdds", "cover-uav-agent-4", "-300");  // not a peer of ours
  auto p = settled(monitor, "/cover-ugv-agent-1", 20s);
  ASSERT_TRUE(p);
  report("peer shifted +50 ms", *p);
  EXPECT_NEAR(ns_to_ms(p->estimate.offset_ns), 50.0, 1.0);
  const auto worst = monitor.largest();
  ASSERT_TRUE(worst);
  EXPECT_EQ(worst->peer, p->peer);
  const std::string reason = monitor.limit_reason().value_or("");
  const std::string head = "clock offset from " + monitor.name() + " to " + p->peer + " is ";
  ASSERT_EQ(reason.rfind(head, 0), 0u) << reason;
  EXPECT_NEAR(std::atof(reason.c_str() + head.size()), 50.0, 1.0) << reason;
  EXPECT_NE(reason.find("(its clock ahead; limit 20 ms)"), std::string::npos) << reason;
  for (const PeerOffset& o : monitor.offsets()) {
    EXPECT_EQ(o.peer.find("cover-uav-agent-4"), std::string::npos) << "not a peer: " << o.peer;
  }

  // The same process restarted without the offset: a new session, a new filter.
  EXPECT_EQ(shifted->terminate(), 0);
  shifted = f.peer("fastdds", "cover-ugv-agent-1");
  ASSERT_TRUE(wait_until([&] { return !monitor.limit_reason(); }, 10s));
  p = settled(monitor, "/cover-ugv-agent-1", 20s);
  ASSERT_TRUE(p);
  report("after the restart", *p);
  EXPECT_LE(std::abs(ns_to_ms(p->estimate.offset_ns)), 1.0);
}

// Forged and malformed traffic on the two topics: counted and dropped, never an estimate,
// never a crash; the real exchange goes on.
TEST(TimeSyncProcess, ForgedRepliesAndMalformedRequestsAreRefused) {
  Fixture f;
  dds::Participant participant(f.options(dds::Vendor::FastDds));
  OffsetMonitor monitor(participant, fast_monitor({"cover-sim"}));
  auto child = f.peer("cyclone", "cover-sim");
  ASSERT_TRUE(settled(monitor, "/cover-sim", 20s));

  dds::Participant intruder(f.options(dds::Vendor::Cyclone));
  auto replies = intruder.make_writer(dds::topics::time_reply("time-sync-test"));
  auto requests = intruder.make_writer(dds::topics::time_request());
  ASSERT_TRUE(replies.wait_for_readers(1, scaled(10s)));
  ASSERT_TRUE(requests.wait_for_readers(1, scaled(10s)));
  const std::int64_t max = std::numeric_limits<std::int64_t>::max();
  const std::uint64_t refused_before = monitor.refused_replies();
  // Written until 20 were refused: best-effort, the first may come before the monitor's
  // reader has matched the intruder's writer (wait_for_readers is the writer's side).
  std::uint64_t written = 0;
  const bool refused_20 = wait_until(
      [&] {
        const std::uint64_t i = written++;
        msg::TimeSyncReply forged;
        forged.requester = monitor.name();
        forged.responder = "evil/cover-sim";
        forged.responder_session = i;
        forged.request_id = 1 + i % 20;               // an id we may have used...
        forged.t1_ns = static_cast<std::int64_t>(i);  // ...but not our t1
        forged.t2_ns = i % 2 ? max : -max;
        forged.t3_ns = max;
        EXPECT_TRUE(replies.write(forged));
        msg::TimeSyncRequest bad;
        bad.requester = i % 2 ? std::string() : std::string(100000, 'x');
        bad.t1_ns = -max;
        EXPECT_TRUE(requests.write(bad));
        return monitor.refused_replies() >= refused_before + 20;
      },
      10s, 10ms);
  ASSERT_TRUE(refused_20) << monitor.refused_replies() - refused_before << " of " << written
                          << " forged replies refused";
  for (const PeerOffset& p : monitor.offsets()) {
    EXPECT_NE(p.peer, "evil/cover-sim");
    EXPECT_LE(std::abs(ns_to_ms(p.estimate.offset_ns)), 1.0) << p.peer;
  }
  EXPECT_FALSE(monitor.limit_reason());
  EXPECT_EQ(child->terminate(), 0);  // the responder survived the malformed requests
}

// Requests are addressed: a responder answers only the requests that name it (or name no
// one), so a fleet's P processes do not each answer every asker. A station on the domain
// reads every asker's reply topic.
TEST(TimeSyncProcess, AResponderAnswersOnlyTheRequestsThatNameIt) {
  Fixture f;
  dds::Participant participant(f.options(dds::Vendor::FastDds));
  std::mutex mutex;
  std::map<std::string, std::set<std::string>> answered;  // requester -> responders heard
  std::vector<dds::Reader<msg::TimeSyncReply>> replies;
  for (const char* asker : {"time-sync-test", "time-sync-test-all", "time-sync-test-waiting"}) {
    replies.push_back(
        participant.make_reader(dds::topics::time_reply(asker), [&](const msg::TimeSyncReply& r) {
          std::lock_guard<std::mutex> lock(mutex);
          answered[r.requester].insert(r.responder);
        }));
  }
  auto heard = [&](const std::string& requester) {
    std::lock_guard<std::mutex> lock(mutex);
    return answered[requester];
  };
  auto sim = f.peer("fastdds", "cover-sim");
  auto ugv = f.peer("cyclone", "cover-ugv-agent-3");
  OffsetMonitor monitor(participant, fast_monitor({"cover-sim"}));
  ASSERT_TRUE(settled(monitor, "/cover-sim", 20s));
  // 16 burst requests and 1.5 s at 5 Hz: had the UGV agent answered any, it would show.
  const std::set<std::string> only_sim = heard(monitor.name());
  ASSERT_EQ(only_sim.size(), 1u);
  EXPECT_EQ(only_sim.begin()->substr(only_sim.begin()->rfind('/')), "/cover-sim");
  EXPECT_EQ(monitor.offsets().size(), 1u);

  // The same UGV agent answers a monitor that asks everyone: it was up and able to.
  MonitorOptions everyone = fast_monitor({});
  everyone.process = "time-sync-test-all";
  OffsetMonitor all(participant, everyone);
  ASSERT_TRUE(settled(all, "/cover-ugv-agent-3", 20s));
  EXPECT_TRUE(settled(all, "/cover-sim", 5s));

  // Asked from now on: the UGV agent only; the simulator's estimate is dropped at once.
  monitor.set_peers({"cover-ugv-agent-3"});
  for (const PeerOffset& p : monitor.offsets())
    EXPECT_EQ(p.peer.find("/cover-sim"), std::string::npos);
  ASSERT_TRUE(settled(monitor, "/cover-ugv-agent-3", 20s));
  EXPECT_EQ(monitor.offsets().size(), 1u);

  // A monitor waiting for its peers asks no one until one is added.
  MonitorOptions waiting = fast_monitor({});
  waiting.process = "time-sync-test-waiting";
  waiting.wait_for_peers = true;
  OffsetMonitor idle(participant, waiting);
  std::this_thread::sleep_for(scaled(500ms));  // a window in which nothing may be sent
  EXPECT_EQ(idle.requests_sent(), 0u);
  EXPECT_TRUE(heard(idle.name()).empty());
  idle.add_peer("cover-sim");
  ASSERT_TRUE(settled(idle, "/cover-sim", 20s));
  EXPECT_EQ(heard(idle.name()).size(), 1u);
  EXPECT_EQ(sim->terminate(), 0);
  EXPECT_EQ(ugv->terminate(), 0);
}

// Each reply reaches its asker only (cover/time/reply/<process>): four real processes,
// two that answer and two that ask (across vendors), and one asker that asks no one. Every
// reply an asker was delivered is its own, and a topic nobody asks on stays silent; on one
// shared reply topic, each asker would have been delivered the other's replies too.
TEST(TimeSyncProcess, RepliesReachOnlyTheirAsker) {
  Fixture f;
  dds::Participant station(f.options(dds::Vendor::Cyclone));
  struct Heard {
    std::mutex mutex;
    std::map<std::string, std::set<std::string>> by_requester;  // requester -> responders
    std::size_t samples = 0;
  };
  std::map<std::string, Heard> topics;  // by asker; "shared": the old cover/time/reply
  std::vector<dds::Reader<msg::TimeSyncReply>> readers;
  auto listen = [&](const std::string& key, const dds::Topic<msg::TimeSyncReply>& topic) {
    Heard& heard = topics[key];
    readers.push_back(station.make_reader(topic, [&heard](const msg::TimeSyncReply& r) {
      std::lock_guard<std::mutex> lock(heard.mutex);
      heard.by_requester[r.requester].insert(r.responder.substr(r.responder.rfind('/') + 1));
      ++heard.samples;
    }));
  };
  for (const char* asker : {"cover-uav-agent-0", "cover-uav-agent-1", "cover-ugv-agent-5"}) {
    listen(asker, dds::topics::time_reply(asker));
  }
  listen("shared",
         dds::Topic<msg::TimeSyncReply>::uncatalogued("cover/time/reply", dds::exchange_qos()));
  auto snapshot = [&](const std::string& key) {
    Heard& heard = topics.at(key);
    std::lock_guard<std::mutex> lock(heard.mutex);
    return std::make_pair(heard.samples, heard.by_requester);
  };

  auto sim = f.peer("fastdds", "cover-sim");
  auto ugv = f.peer("cyclone", "cover-ugv-agent-3");
  auto uav0 = f.peer("fastdds", "cover-uav-agent-0", "", {"cover-sim"});
  auto uav1 = f.peer("cyclone", "cover-uav-agent-1", "", {"cover-sim", "cover-ugv-agent-3"});
  auto idle = f.peer("fastdds", "cover-ugv-agent-5", "", {"--wait"});
  // Both askers answered many times (a burst of 16 at 20 Hz, then 5 Hz).
  ASSERT_TRUE(wait_until(
      [&] {
        const auto [n0, who0] = snapshot("cover-uav-agent-0");
        const auto [n1, who1] = snapshot("cover-uav-agent-1");
        return n0 >= 20 && n1 >= 40 && who1.size() == 1 && who1.begin()->second.size() == 2;
      },
      20s))
      << snapshot("cover-uav-agent-0").first << " and " << snapshot("cover-uav-agent-1").first
      << " replies";

  // What each asker was delivered, in its own process.
  auto delivered = [](process::ChildProcess& child) {
    EXPECT_EQ(child.terminate(), 0);
    // Its log lines come first on stdout (spdlog's default sink).
    std::string line = "<nothing>";
    while (const auto next = child.read_line(scaled(5s))) {
      line = *next;
      if (line.rfind("delivered ", 0) == 0) break;
    }
    unsigned long long all = 0, foreign = 0;
    std::size_t peers = 0;
    EXPECT_EQ(
        std::sscanf(line.c_str(), "delivered %llu foreign %llu peers %zu", &all, &foreign, &peers),
        3)
        << line;
    std::printf("[ measured ] %s\n", line.c_str());
    return std::make_tuple(all, foreign, peers);
  };
  const auto [all0, foreign0, peers0] = delivered(*uav0);
  const auto [all1, foreign1, peers1] = delivered(*uav1);
  const auto [all_idle, foreign_idle, peers_idle] = delivered(*idle);
  EXPECT_GE(all0, 10u);
  EXPECT_EQ(foreign0, 0u) << "replies to another asker reached cover-uav-agent-0";
  EXPECT_EQ(peers0, 1u);
  EXPECT_GE(all1, 20u);
  EXPECT_EQ(foreign1, 0u) << "replies to another asker reached cover-uav-agent-1";
  EXPECT_EQ(peers1, 2u);
  EXPECT_EQ(all_idle, 0u) << "an asker that asked no one was delivered replies";

  // On each asker's topic, its own replies only, from the peers it asked.
  const auto [n0, who0] = snapshot("cover-uav-agent-0");
  ASSERT_EQ(who0.size(), 1u);
  EXPECT_EQ(who0.begin()->first.substr(who0.begin()->first.rfind('/')), "/cover-uav-agent-0");
  EXPECT_EQ(who0.begin()->second, std::set<std::string>{"cover-sim"});
  const auto [n1, who1] = snapshot("cover-uav-agent-1");
  ASSERT_EQ(who1.size(), 1u);
  EXPECT_EQ(who1.begin()->first.substr(who1.begin()->first.rfind('/')), "/cover-uav-agent-1");
  EXPECT_EQ(who1.begin()->second, (std::set<std::string>{"cover-sim", "cover-ugv-agent-3"}));
  EXPECT_EQ(snapshot("cover-ugv-agent-5").first, 0u);
  EXPECT_EQ(snapshot("shared").first, 0u) << "replies still go out on cover/time/reply";
  std::printf("[ measured ] replies on the askers' topics: %zu (uav-agent-0), %zu (uav-agent-1)\n",
              n0, n1);
  EXPECT_EQ(sim->terminate(), 0);
  EXPECT_EQ(ugv->terminate(), 0);
}

}  // namespace
}  // namespace cover::time_sync

namespace cover::time_sync {
namespace {

// A fleet's askers arrive together: their first requests wait for their reply writers to
// match their readers side by side. Ten askers that never read their replies (they asked
// first) do not hold up the one that does: its first reply comes while their waits (1 s
// each) still run. One after the other, it would come after all ten were given up (measured
// so: 10 of 11 answered first, 10 s). One vendor on both sides: across vendors a writer can
// see a reader matched before the reader matched it, and a single reply is then lost.
TEST(TimeSyncProcess, NewAskersWaitForTheirReadersSideBySide) {
  Fixture f;
  dds::Participant answering(f.options(dds::Vendor::FastDds));
  ClockResponder responder(answering, "cover-sim");
  dds::Participant asking(f.options(dds::Vendor::FastDds));
  // The replies counted when the reader's first reply came (this one may not be counted yet:
  // delivered before the responder's count); -1 before it came.
  std::atomic<std::int64_t> answered_at_first_reply{-1};
  auto replies = asking.make_reader(dds::topics::time_reply("cover-uav-agent-0"),
                                    [&](const msg::TimeSyncReply&) {
                                      std::int64_t none = -1;
                                      answered_at_first_reply.compare_exchange_strong(
                                          none, static_cast<std::int64_t>(responder.answered()));
                                    });
  auto requests = asking.make_writer(dds::topics::time_request());
  ASSERT_TRUE(requests.wait_for_readers(1, scaled(10s)));
  const auto request = [&](const std::string& process, std::uint64_t id) {
    msg::TimeSyncRequest r;
    r.requester = "test-host/" + process;
    r.request_id = id;
    r.t1_ns = 1;
    EXPECT_TRUE(requests.write(r));
  };
  constexpr int kSilentAskers = 10;
  for (int k = 0; k < kSilentAskers; ++k) request("cover-silent-" + std::to_string(k), 1);
  request("cover-uav-agent-0", 1);
  ASSERT_TRUE(wait_until([&] { return answered_at_first_reply.load() >= 0; }, 20s))
      << "no reply to the asker that reads them; answered " << responder.answered();
  // Each of the askers' first requests came before its writer: held, then answered.
  ASSERT_TRUE(wait_until([&] { return responder.answered() == kSilentAskers + 1; }, 20s))
      << responder.answered();
  EXPECT_EQ(responder.unanswered(), static_cast<std::uint64_t>(kSilentAskers + 1));
  // One after the other: 10 or 11 (every silent asker's wait given up first).
  EXPECT_LT(answered_at_first_reply.load(), kSilentAskers / 2)
      << "the asker's first reply waited for the silent askers' waits";
  std::printf("[ measured ] answered when the reading asker's first reply came: %lld of %d\n",
              static_cast<long long>(answered_at_first_reply.load()), kSilentAskers + 1);
}

}  // namespace
}  // namespace cover::time_sync
