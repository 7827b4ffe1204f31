// The four-timestamp estimator from worked examples (times in ms, as NTP's texts give them).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>

#include "cover/config/config_error.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/shipped_params.hpp"
#include "cover/time_sync/exchange.hpp"
#include "cover/time_sync/offset_filter.hpp"
#include "cover/time_sync/peer_name.hpp"
#include "cover/time_sync/peer_offsets.hpp"
#include "cover/time_sync/time_sync_params.hpp"

namespace cover::time_sync {
namespace {

constexpr std::int64_t kMs = 1'000'000;

Exchange exchange_ms(double t1, double t2, double t3, double t4) {
  auto ns = [](double ms) { return static_cast<std::int64_t>(ms * 1e6); };
  return {ns(t1), ns(t2), ns(t3), ns(t4)};
}

TEST(Exchange, PeerAheadSymmetricLegs) {
  // Peer 5 ms ahead, 1 ms each way, the peer holds the request 1 ms:
  // t2 = 0 + 1 + 5, t3 = t2 + 1, t4 = t3 - 5 + 1.
  const auto s = measure(exchange_ms(0, 6, 7, 3));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->offset_ns, 5 * kMs);
  EXPECT_EQ(s->delay_ns, 2 * kMs);
  EXPECT_EQ(s->received_ns, 3 * kMs);
}

TEST(Exchange, PeerBehindOnEpochTimes) {
  // Peer 100 ms behind, 0.5 ms each way, held 0.2 ms; epoch-sized times.
  const std::int64_t base = 1'764'000'000'000'000'000;
  const Exchange e{base, base + 500'000 - 100 * kMs, base + 700'000 - 100 * kMs, base + 1'200'000};
  const auto s = measure(e);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->offset_ns, -100 * kMs);
  EXPECT_EQ(s->delay_ns, 1 * kMs);
}

TEST(Exchange, AsymmetricLegsErrIsHalfTheDifferenceWithinHalfTheDelay) {
  // Same clocks, 3 ms out, 1 ms back: the estimate is off by (3 - 1) / 2 = 1 ms, and the
  // uncertainty (delay / 2 = 2 ms) covers it.
  const auto s = measure(exchange_ms(0, 3, 3, 4));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->offset_ns, 1 * kMs);
  EXPECT_EQ(s->delay_ns, 4 * kMs);
  OffsetFilter filter;
  filter.add(*s);
  EXPECT_GE(filter.estimate(4 * kMs)->uncertainty_ns, std::abs(s->offset_ns));
}

TEST(Exchange, ImpossibleTimesAreRefused) {
  EXPECT_FALSE(measure(exchange_ms(10, 11, 12, 9)));  // the reply before the request
  EXPECT_FALSE(measure(exchange_ms(0, 12, 11, 5)));   // sent before it was received
  EXPECT_FALSE(measure(exchange_ms(0, 1, 9, 5)));     // held longer than the round trip
  const std::int64_t max = std::numeric_limits<std::int64_t>::max();
  const std::int64_t min = std::numeric_limits<std::int64_t>::min();
  EXPECT_FALSE(measure({min, max, max, 0}));  // overflow, not a wrapped offset
  EXPECT_FALSE(measure({0, max, max, 1}));
  EXPECT_TRUE(measure({0, 0, 0, 0}));  // a zero delay is possible at ns resolution
}

TEST(OffsetFilter, KeepsTheLeastDelayOfTheWindow) {
  OffsetFilter filter(3);
  EXPECT_FALSE(filter.estimate(0));
  filter.add({10 * kMs, 8 * kMs, 100 * kMs});  // a slow exchange: offset off by 4 ms
  filter.add({6 * kMs, 1 * kMs, 200 * kMs});   // the quick one
  filter.add({9 * kMs, 5 * kMs, 300 * kMs});
  auto e = filter.estimate(1200 * kMs);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->offset_ns, 6 * kMs);
  EXPECT_EQ(e->delay_ns, 1 * kMs);
  EXPECT_EQ(e->uncertainty_ns, kMs / 2);
  EXPECT_EQ(e->age_ns, 1000 * kMs);
  // Three more push the quick one out of the window.
  filter.add({7 * kMs, 2 * kMs, 400 * kMs});
  filter.add({8 * kMs, 3 * kMs, 500 * kMs});
  filter.add({5 * kMs, 4 * kMs, 600 * kMs});
  e = filter.estimate(600 * kMs);
  EXPECT_EQ(e->offset_ns, 7 * kMs);
  EXPECT_EQ(e->age_ns, 200 * kMs);
  // Equal delays: the newer sample.
  filter.add({1 * kMs, 2 * kMs, 700 * kMs});
  EXPECT_EQ(filter.estimate(700 * kMs)->offset_ns, 1 * kMs);
  EXPECT_EQ(filter.size(), 3u);
}

TEST(PeerOffsets, OnePeerPerNameANewSessionStartsAfresh) {
  PeerOffsets peers(8, 5000 * kMs);
  EXPECT_FALSE(peers.largest(0));
  EXPECT_FALSE(peers.add("h1/cover-sim", 7, {50 * kMs, 1 * kMs, 100 * kMs}));
  EXPECT_TRUE(peers.add("h1/cover-sim", 7, {52 * kMs, 3 * kMs, 200 * kMs}));
  EXPECT_FALSE(peers.add("h2/cover-ugv-agent-1", 9, {-70 * kMs, 1 * kMs, 200 * kMs}));
  auto worst = peers.largest(200 * kMs);
  ASSERT_TRUE(worst);
  EXPECT_EQ(worst->peer, "h2/cover-ugv-agent-1");
  EXPECT_EQ(worst->estimate.offset_ns, -70 * kMs);
  // The UGV agent restarts with a good clock: its old, quicker sample does not survive.
  EXPECT_FALSE(peers.add("h2/cover-ugv-agent-1", 10, {0, 2 * kMs, 300 * kMs}));
  worst = peers.largest(300 * kMs);
  EXPECT_EQ(worst->peer, "h1/cover-sim");
  EXPECT_EQ(worst->estimate.offset_ns, 50 * kMs);
  EXPECT_EQ(peers.all(300 * kMs).size(), 2u);
}

TEST(PeerOffsets, SilentPeersAreForgotten) {
  PeerOffsets peers(8, 5000 * kMs);
  peers.add("a/x", 1, {1, 1, 0});
  peers.add("b/y", 1, {2, 1, 4000 * kMs});
  EXPECT_TRUE(peers.forget_silent(5000 * kMs).empty());
  EXPECT_EQ(peers.forget_silent(5001 * kMs), std::vector<std::string>{"a/x"});
  EXPECT_EQ(peers.all(5001 * kMs).size(), 1u);
}

TEST(PeerOffsets, LimitReasonNamesBothHostsAndTheOffset) {
  PeerOffset peer{"h2/cover-ugv-agent-1", {52'300'000, 400'000, 200'000, 0}};
  EXPECT_EQ(offset_limit_reason("h1/cover-uav-agent-0", peer, 20.0).value_or(""),
            "clock offset from h1/cover-uav-agent-0 to h2/cover-ugv-agent-1 is 52.3 ms (its "
            "clock ahead; limit 20 ms)");
  peer.estimate.offset_ns = -25 * kMs;
  EXPECT_NE(offset_limit_reason("a", peer, 20.0).value_or("").find("25.0 ms (its clock behind"),
            std::string::npos);
  peer.estimate.offset_ns = 20 * kMs;  // at the limit: allowed
  EXPECT_FALSE(offset_limit_reason("a", peer, 20.0));
}

TEST(PeerName, HostSlashProcessAndPatterns) {
  const std::string me = peer_name("cover-uav-agent-0");
  EXPECT_NE(me.find("/cover-uav-agent-0"), std::string::npos);
  EXPECT_GT(me.find('/'), 0u);
  const std::vector<std::string> uav0{"cover-sim", "cover-ugv-agent-*", "cover-fc-bridge-0"};
  EXPECT_TRUE(peer_matches("lab/cover-sim", uav0));
  EXPECT_TRUE(peer_matches("ugv1-pi/cover-ugv-agent-1", uav0));
  EXPECT_TRUE(peer_matches("nx/cover-fc-bridge-0", uav0));
  EXPECT_FALSE(peer_matches("nx/cover-fc-bridge-01", uav0));
  EXPECT_FALSE(peer_matches("lab/cover-simulator", uav0));
  EXPECT_FALSE(peer_matches("lab/cover-uav-agent-1", uav0));
  EXPECT_FALSE(peer_matches("cover-sim/evil", uav0));  // the process is after the last '/'
  EXPECT_TRUE(peer_matches("anything", {}));
}

// Every field (TimeSyncParams::fields), shipped with its default value.
TEST(TimeSyncParams, ShippedFileHoldsTheDefaults) {
  const std::string path = std::string(COVER_CONFIG_DIR) + "/time_sync.yaml";
  cover::test::expect_shipped_file_holds_defaults(TimeSyncParams::load_file(path), path,
                                                  "time_sync");
  EXPECT_EQ(TimeSyncParams::load_file(path).max_offset_ms, 20.0);
}

TEST(TimeSyncParams, BadKeysAndValuesAreNamed) {
  auto load = [](const std::string& text) {
    return TimeSyncParams::from_yaml(config::parse_yaml(text, "t.yaml"), "t.yaml");
  };
  EXPECT_EQ(load("time_sync: {max_offset_ms: 5}").max_offset_ms, 5.0);
  EXPECT_EQ(load("{}").max_offset_ms, 20.0);  // a missing section: the defaults
  auto error_of = [&](const std::string& text) {
    try {
      load(text);
    } catch (const config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("time_sync: {max_ofset_ms: 5}").find("max_ofset_ms"), std::string::npos);
  EXPECT_NE(error_of("time_sync: {max_offset_ms: -1}").find("time_sync.max_offset_ms"),
            std::string::npos);
  EXPECT_NE(error_of("time_sync: {peer_timeout_s: 0.5}").find("time_sync.peer_timeout_s"),
            std::string::npos);
}

TEST(TimeSyncParams, LoadBesideAProcesssOwnConfig) {
  // The UGV agent and the task manager read time_sync.yaml beside their --config file.
  const std::string dir = cover::test::scratch_path("with");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/time_sync.yaml") << "time_sync:\n  max_offset_ms: 7.5\n";
  EXPECT_EQ(TimeSyncParams::load_beside(dir + "/task_manager.yaml").max_offset_ms, 7.5);
  const std::string empty = cover::test::scratch_path("without");
  std::filesystem::create_directories(empty);
  EXPECT_EQ(TimeSyncParams::load_beside(empty + "/ugv_agent.yaml").max_offset_ms, 20.0);
  std::ofstream(dir + "/time_sync.yaml") << "time_sync:\n  max_offset_ms: -1\n";
  EXPECT_THROW(TimeSyncParams::load_beside(dir + "/x.yaml"), config::ConfigError);
}

}  // namespace
}  // namespace cover::time_sync
