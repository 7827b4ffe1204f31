// cover-foxglove-bridge as Foxglove meets it, checked by an independent client
// (@foxglove/ws-protocol's FoxgloveClient over `ws`, decoding with
// @foxglove/omgidl-serialization from the advertised schema): every catalogued topic of the
// fleet advertised (cdr / omgidl), subscribed samples decoded to the published values, the
// 3D channels (FrameTransform, SceneUpdate) from relative states and a reference; a client
// that stops reading delays neither the other client nor the publishers and is dropped;
// a malformed message earns an error status for its sender only. Skips only without Node.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <thread>

#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/recording/fleet_topics.hpp"
#include "foxglove_test_support.hpp"
#include "published_samples.hpp"

namespace cover::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using nlohmann::json;

constexpr std::int64_t kWarmUpEndNs = 1'000'000'000;

// Messages on `topic` of the counted samples, those stamped after the warm-up's.
std::size_t counted_messages(const std::vector<json>& lines, const std::string& topic) {
  std::size_t n = 0;
  for (const auto& l : lines) {
    if (!l.is_object() || l.value("event", "") != "message" || l.value("topic", "") != topic) {
      continue;
    }
    const auto value = l.find("value");
    if (value == l.end() || !value->is_object() || !value->contains("stamp_ns")) continue;
    const json& stamp = (*value)["stamp_ns"];
    if (stamp.is_string() && std::stoll(stamp.get<std::string>()) >= kWarmUpEndNs) ++n;
  }
  return n;
}

class FoxgloveBridge : public ::testing::Test {
 protected:
  void SetUp() override {
    if (find_node().empty()) GTEST_SKIP() << "node is not installed: the bridge tests need Node";
    ASSERT_TRUE(fs::exists(fs::path(COVER_FOXGLOVE_PEER_DIR) / "node_modules" / "@foxglove" /
                           "ws-protocol" / "package.json"))
        << "the Foxglove client is not installed: run scripts/setup (npm ci --prefix "
           "tests/foxglove/peer)";
    claim_.emplace(dds::DomainClaim::claim_any(160, 164));
    dds::ParticipantOptions options;
    options.vendor = dds::Vendor::FastDds;
    options.domain_id = claim_->domain();
    participant_.emplace(options);
  }

  std::unique_ptr<BridgeProcess> start_bridge(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{"--uavs", "1", "--ugvs", "2"};
    args.insert(args.end(), extra.begin(), extra.end());
    return std::make_unique<BridgeProcess>(claim_->domain(), args, "bridge.log");
  }

  std::optional<dds::DomainClaim> claim_;
  std::optional<dds::Participant> participant_;
};

std::size_t fleet_topic_count(std::uint32_t uavs, std::uint32_t ugvs) {
  std::size_t n = 0;
  recording::for_each_fleet_topic(recording::FleetSize{uavs, ugvs}, [&](const auto&) { ++n; });
  return n;
}

TEST_F(FoxgloveBridge, AdvertisesTheFleetAndStreamsSamplesDecodedToThePublishedValues) {
  auto bridge = start_bridge();
  NodeClient client(
      bridge->url(),
      {{"subscribe", {"cover/ugv/1/imu", "cover/uav/0/reference", "cover/task/request"}},
       {"duration_ms", 60000}},
      "client");
  ASSERT_TRUE(client.wait_for([](const auto& l) { return count_event(l, "advertise") >= 1; }, 20s));
  const auto info = client.events("serverInfo");
  ASSERT_EQ(info.size(), 1u);
  EXPECT_EQ(info[0]["name"], "cover-foxglove-bridge");
  EXPECT_EQ(client.events("open")[0]["protocol"], "foxglove.websocket.v1");

  std::map<std::string, json> advertised;
  for (const auto& a : client.events("advertise")) {
    for (const auto& c : a["channels"]) advertised[c["topic"]] = c;
  }
  EXPECT_EQ(advertised.size(), fleet_topic_count(1, 2) + 2) << "every catalogued topic + tf, scene";
  for (const auto& [topic, c] : advertised) {
    if (topic.rfind("cover/foxglove/", 0) == 0) {
      EXPECT_EQ(c["encoding"], "json") << topic;
      EXPECT_EQ(c["schemaEncoding"], "jsonschema") << topic;
    } else {
      EXPECT_EQ(c["encoding"], "cdr") << topic;
      EXPECT_EQ(c["schemaEncoding"], "omgidl") << topic;
    }
  }
  EXPECT_EQ(advertised["cover/uav/0/rel/1"]["schemaName"], "cover::idl::RelativeState");
  EXPECT_EQ(advertised["cover/foxglove/tf"]["schemaName"], "foxglove.FrameTransform");
  EXPECT_EQ(advertised["cover/foxglove/scene"]["schemaName"], "foxglove.SceneUpdate");

  auto imu = participant_->make_writer(dds::topics::ugv_imu(1));
  auto reference = participant_->make_writer(dds::topics::uav_reference(0));
  auto task = participant_->make_writer(dds::topics::task_request());
  ASSERT_TRUE(imu.wait_for_readers(1, scaled(20s)) && reference.wait_for_readers(1, scaled(20s)) &&
              task.wait_for_readers(1, scaled(20s)));
  // Until the client has a sample of each topic: the subscription reached the bridge.
  for (std::int64_t n = 1;; ++n) {
    imu.write(warm(imu_sample(0), n));
    reference.write(warm(reference_sample(0, 3), n));
    task.write(warm(task_sample(0), n));
    if (client.wait_for(
            [](const auto& l) {
              return count_event(l, "message", "cover/ugv/1/imu") > 0 &&
                     count_event(l, "message", "cover/uav/0/reference") > 0 &&
                     count_event(l, "message", "cover/task/request") > 0;
            },
            50ms)) {
      break;
    }
    ASSERT_LT(n, 400) << "no sample reached the client";
  }
  std::map<std::string, json> published;  // by topic + stamp
  constexpr std::uint32_t kSamples = 40;
  for (std::uint32_t i = 0; i < kSamples; ++i) {
    imu.write(imu_sample(i));
    reference.write(reference_sample(i, 3 + i));
    task.write(task_sample(i));
    published["cover/ugv/1/imu" + std::to_string(imu_sample(i).stamp_ns)] =
        decoded_form(imu_sample(i));
    published["cover/uav/0/reference" + std::to_string(reference_sample(i, 3 + i).stamp_ns)] =
        decoded_form(reference_sample(i, 3 + i));
    published["cover/task/request" + std::to_string(task_sample(i).stamp_ns)] =
        decoded_form(task_sample(i));
    std::this_thread::sleep_for(5ms);  // pacing a 200 Hz publisher, not synchronisation
  }
  ASSERT_TRUE(client.wait_for(
      [&](const auto& l) {
        return counted_messages(l, "cover/uav/0/reference") >= kSamples &&
               counted_messages(l, "cover/task/request") >= kSamples;
      },
      20s));
  std::map<std::string, std::size_t> counts;
  const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::system_clock::now().time_since_epoch())
                          .count();
  for (const auto& m : client.events("message")) {
    const std::string topic = m["topic"];
    const std::string stamp = m["value"]["stamp_ns"];
    if (std::stoll(stamp) < kWarmUpEndNs) continue;
    const auto expected = published.find(topic + stamp);
    ASSERT_NE(expected, published.end()) << m.dump();
    EXPECT_EQ(m["value"], expected->second) << topic;
    const auto log_time = std::stoll(m["log_time"].get<std::string>());
    EXPECT_LT(std::abs(now_ns - log_time), 60'000'000'000LL) << "log time = receive time";
    ++counts[topic];
  }
  EXPECT_EQ(counts["cover/uav/0/reference"], kSamples);
  EXPECT_EQ(counts["cover/task/request"], kSamples);
  EXPECT_GE(counts["cover/ugv/1/imu"], kSamples - 2) << "best effort, on one host";
  EXPECT_TRUE(client.events("error").empty()) << client.events("error")[0].dump();

  EXPECT_EQ(bridge->child().terminate(scaled(10s), SIGINT), 0);
  EXPECT_NE(read_text(bridge->log()).find("bridge CPU"), std::string::npos);
}

TEST_F(FoxgloveBridge, ShowsTheUgvFramesTheUavAndItsReferenceIn3d) {
  auto bridge = start_bridge({"--scene-rate-hz", "20"});
  NodeClient client(bridge->url(),
                    {{"subscribe", {"cover/foxglove/tf", "cover/foxglove/scene"}},
                     {"subprotocol", "foxglove.sdk.v1"},
                     {"duration_ms", 60000}},
                    "client_3d");
  auto rel0 = participant_->make_writer(dds::topics::relative_state(0, 0));
  auto rel1 = participant_->make_writer(dds::topics::relative_state(0, 1));
  auto reference = participant_->make_writer(dds::topics::uav_reference(0));
  ASSERT_TRUE(rel0.wait_for_readers(1, scaled(20s)) && rel1.wait_for_readers(1, scaled(20s)) &&
              reference.wait_for_readers(1, scaled(20s)));
  msg::RelativeState in0;
  in0.uav_id = 0;
  in0.ugv_id = 0;
  in0.valid = true;
  in0.position_m = {1.0, 2.0, 3.0};
  in0.attitude = {1.0, 0.0, 0.0, 0.0};
  msg::RelativeState in1 = in0;
  in1.ugv_id = 1;
  in1.position_m = {-4.0, 0.5, 2.0};
  in1.attitude = {std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)};  // 90 deg about z
  reference.write(reference_sample(7, 5));
  const auto has_both = [](const std::vector<json>& lines) {
    bool tf1 = false;
    bool scene = false;
    for (const auto& l : lines) {
      if (l.value("event", "") != "message") continue;
      if (l["topic"] == "cover/foxglove/tf" && l["value"]["child_frame_id"] == "ugv_1") tf1 = true;
      if (l["topic"] == "cover/foxglove/scene" && l["value"]["entities"].size() == 4) scene = true;
    }
    return tf1 && scene;
  };
  for (int n = 0; !client.wait_for(has_both, 20ms); ++n) {
    in0.stamp_ns = in1.stamp_ns = n;
    rel0.write(in0);
    rel1.write(in1);
    ASSERT_LT(n, 1000) << "no transform of ugv_1 and full scene reached the client";
  }
  json tf0, tf1, scene;
  for (const auto& m : client.events("message")) {
    if (m["topic"] == "cover/foxglove/tf" && m["value"]["child_frame_id"] == "uav_0")
      tf0 = m["value"];
    if (m["topic"] == "cover/foxglove/tf" && m["value"]["child_frame_id"] == "ugv_1")
      tf1 = m["value"];
    if (m["topic"] == "cover/foxglove/scene" && m["value"]["entities"].size() == 4)
      scene = m["value"];
  }
  EXPECT_EQ(tf0["parent_frame_id"], "ugv_0");
  EXPECT_EQ(tf0["translation"], (json{{"x", 1.0}, {"y", 2.0}, {"z", 3.0}}));
  // ugv_1 in uav_0: the inverse of the UAV's pose in G_1 (R = 90 deg about z).
  EXPECT_EQ(tf1["parent_frame_id"], "uav_0");
  EXPECT_NEAR(tf1["translation"]["x"].get<double>(), -0.5, 1e-9);
  EXPECT_NEAR(tf1["translation"]["y"].get<double>(), -4.0, 1e-9);
  EXPECT_NEAR(tf1["translation"]["z"].get<double>(), -2.0, 1e-9);
  EXPECT_NEAR(tf1["rotation"]["z"].get<double>(), -std::sqrt(0.5), 1e-9);
  std::map<std::string, json> entities;
  for (const auto& e : scene["entities"]) entities[e["id"]] = e;
  ASSERT_EQ(entities.size(), 4u) << scene.dump();
  EXPECT_EQ(entities["ugv_0"]["frame_id"], "ugv_0");
  EXPECT_EQ(entities["ugv_1"]["cubes"].size(), 1u) << "the deck";
  EXPECT_EQ(entities["uav_0"]["frame_id"], "uav_0");
  EXPECT_EQ(entities["reference_0"]["frame_id"], "ugv_1") << "the reference UGV's frame";
  ASSERT_EQ(entities["reference_0"]["lines"][0]["points"].size(), 5u);
  EXPECT_EQ(entities["reference_0"]["lines"][0]["points"][4],
            (json{{"x", 4.0}, {"y", 14.0}, {"z", -0.5}}));
}

struct Timing {
  double p50_latency_ms = 0;
  double p99_latency_ms = 0;
  double max_gap_ms = 0;
  std::size_t messages = 0;
};

// The IMU messages a client received with log times in [from_ns, to_ns).
Timing timing(const std::vector<json>& lines, std::int64_t from_ns, std::int64_t to_ns) {
  std::vector<double> latency;
  std::vector<std::int64_t> arrivals;
  for (const auto& l : lines) {
    if (l.value("event", "") != "message" || l["topic"] != "cover/ugv/0/imu") continue;
    const auto log_time = std::stoll(l["log_time"].get<std::string>());
    if (log_time < from_ns || log_time >= to_ns) continue;
    const auto recv = std::stoll(l["recv_ns"].get<std::string>());
    latency.push_back((recv - log_time) * 1e-6);
    arrivals.push_back(recv);
  }
  Timing t;
  t.messages = latency.size();
  if (latency.empty()) return t;
  std::sort(latency.begin(), latency.end());
  t.p50_latency_ms = latency[latency.size() / 2];
  t.p99_latency_ms = latency[static_cast<std::size_t>(0.99 * (latency.size() - 1))];
  for (std::size_t i = 1; i < arrivals.size(); ++i) {
    t.max_gap_ms = std::max(t.max_gap_ms, (arrivals[i] - arrivals[i - 1]) * 1e-6);
  }
  return t;
}

std::int64_t system_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

TEST_F(FoxgloveBridge, AClientThatStopsReadingDelaysNeitherTheOtherClientNorThePublishers) {
  auto bridge = start_bridge({"--client-queue-kib", "256", "--slow-client-timeout-s", "2"});
  NodeClient reader(bridge->url(), {{"subscribe", {"cover/ugv/0/imu"}}, {"duration_ms", 60000}},
                    "reader");
  ASSERT_TRUE(reader.wait_for([](const auto& l) { return count_event(l, "advertise") >= 1; }, 20s));
  std::size_t channels = 0;
  for (const auto& a : reader.events("advertise")) channels += a["channels"].size();

  // The publishers: the IMU the reader watches at 200 Hz, and a heavy reference (3000
  // points, 72 KB) at 50 Hz that only the slow client subscribes to. Each write is timed.
  auto imu = participant_->make_writer(dds::topics::ugv_imu(0));
  auto heavy = participant_->make_writer(dds::topics::uav_reference(0));
  ASSERT_TRUE(imu.wait_for_readers(1, scaled(20s)) && heavy.wait_for_readers(1, scaled(20s)));
  std::atomic<bool> publishing{true};
  std::mutex write_mutex;
  std::vector<std::pair<std::int64_t, double>> writes;  // (system ns, write ms)
  std::thread publisher([&] {
    msg::UgvImu s = imu_sample(0);
    s.ugv_id = 0;
    const msg::ReferenceTrajectory big = reference_sample(1, 3000);
    for (std::uint32_t i = 0; publishing; ++i) {
      s.seq = i;
      s.stamp_ns = system_now_ns();
      const auto t0 = std::chrono::steady_clock::now();
      imu.write(s);
      if (i % 4 == 0) heavy.write(big);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      {
        std::lock_guard<std::mutex> lock(write_mutex);
        writes.emplace_back(system_now_ns(), ms);
      }
      std::this_thread::sleep_for(5ms);  // pacing a 200 Hz publisher
    }
  });
  const auto max_write_ms = [&](std::int64_t from_ns, std::int64_t to_ns) {
    std::lock_guard<std::mutex> lock(write_mutex);
    double worst = 0;
    for (const auto& [at, ms] : writes) {
      if (at >= from_ns && at < to_ns) worst = std::max(worst, ms);
    }
    return worst;
  };

  ASSERT_TRUE(reader.wait_for([](const auto& l) { return count_event(l, "message") > 0; }, 20s));
  const std::int64_t baseline_from = system_now_ns();
  ASSERT_TRUE(poll_until([&] { return system_now_ns() - baseline_from > 3'000'000'000LL; }, 10s));
  const std::int64_t slow_from = system_now_ns();

  // The slow client: subscribes to every channel, then never reads.
  RawClient slow(bridge->port(), "foxglove.websocket.v1");
  ASSERT_NE(slow.response().find("101"), std::string::npos) << slow.response();
  json subscriptions = json::array();
  for (std::size_t id = 1; id <= channels; ++id)
    subscriptions.push_back({{"id", id}, {"channelId", id}});
  slow.send_text(json{{"op", "subscribe"}, {"subscriptions", subscriptions}}.dump());
  ASSERT_TRUE(poll_until(
      [&] { return read_text(bridge->log()).find("is not keeping up") != std::string::npos; }, 20s))
      << "the slow client's queue never filled: see " << bridge->log();
  ASSERT_TRUE(poll_until(
      [&] {
        return read_text(bridge->log()).find("disconnected: its queue was full") !=
               std::string::npos;
      },
      20s))
      << "the slow client was not dropped: see " << bridge->log();
  const std::int64_t slow_to = system_now_ns();
  publishing = false;
  publisher.join();
  EXPECT_TRUE(slow.closed_by_server(10s)) << "the bridge closed the slow client's connection";

  const auto lines = reader.lines();
  const Timing baseline = timing(lines, baseline_from, slow_from);
  const Timing with_slow = timing(lines, slow_from, slow_to);
  const double write_baseline_ms = max_write_ms(baseline_from, slow_from);
  const double write_slow_ms = max_write_ms(slow_from, slow_to);
  std::cout << "reading client, IMU at 200 Hz: baseline " << baseline.messages
            << " messages, latency p50 " << baseline.p50_latency_ms << " ms p99 "
            << baseline.p99_latency_ms << " ms, max gap " << baseline.max_gap_ms
            << " ms; with a client not reading (" << (slow_to - slow_from) * 1e-9
            << " s until dropped) " << with_slow.messages << " messages, p50 "
            << with_slow.p50_latency_ms << " ms p99 " << with_slow.p99_latency_ms << " ms, max gap "
            << with_slow.max_gap_ms << " ms; publisher's slowest write " << write_baseline_ms
            << " ms -> " << write_slow_ms << " ms" << std::endl;
  ASSERT_GT(baseline.messages, 300u);
  const double seconds = (slow_to - slow_from) * 1e-9;
  EXPECT_GT(with_slow.messages, 0.8 * 200 * seconds) << "the reading client kept receiving";
  EXPECT_LT(with_slow.p99_latency_ms,
            std::max(3 * baseline.p99_latency_ms, baseline.p99_latency_ms + 25));
  EXPECT_LT(with_slow.max_gap_ms, baseline.max_gap_ms + 100);
  EXPECT_LT(write_slow_ms, std::max(3 * write_baseline_ms, write_baseline_ms + 20));
}

TEST_F(FoxgloveBridge, AMalformedMessageGetsAnErrorStatusOnlyToItsSender) {
  auto bridge = start_bridge();
  NodeClient bad(bridge->url(),
                 {{"subscribe", {"cover/ugv/0/imu"}}, {"malformed", true}, {"duration_ms", 60000}},
                 "bad");
  NodeClient good(bridge->url(),
                  {{"subscribe", {"cover/ugv/0/imu"}},
                   {"subprotocol", "foxglove.sdk.v1"},
                   {"duration_ms", 60000}},
                  "good");
  auto imu = participant_->make_writer(dds::topics::ugv_imu(0));
  ASSERT_TRUE(imu.wait_for_readers(1, scaled(20s)));
  msg::UgvImu s = imu_sample(0);
  s.ugv_id = 0;
  const auto both_receive_after = [&](std::size_t bad_count, std::size_t good_count) {
    for (std::uint32_t i = 0;; ++i) {
      s.seq = i;
      s.stamp_ns = i + 1;
      imu.write(s);
      if (bad.wait_for([&](const auto& l) { return count_event(l, "message") > bad_count; },
                       10ms) &&
          good.wait_for([&](const auto& l) { return count_event(l, "message") > good_count; },
                        10ms)) {
        return true;
      }
      if (i > 2000) return false;
    }
  };
  ASSERT_TRUE(both_receive_after(0, 0));
  ASSERT_TRUE(bad.wait_for([](const auto& l) { return count_event(l, "status") >= 3; }, 20s));
  // After its errors the sender is still served, and so is the other client.
  ASSERT_TRUE(both_receive_after(bad.events("message").size(), good.events("message").size()));
  const auto statuses = bad.events("status");
  ASSERT_EQ(statuses.size(), 3u);
  for (const auto& status : statuses) {
    EXPECT_EQ(status["level"], 2) << status.dump();
    EXPECT_FALSE(status["message"].get<std::string>().empty());
  }
  EXPECT_TRUE(good.events("status").empty()) << good.events("status")[0].dump();
  EXPECT_TRUE(bad.events("close").empty()) << "the sender stays connected";
  EXPECT_EQ(good.events("open")[0]["protocol"], "foxglove.sdk.v1");

  // A client offering neither subprotocol is refused at the handshake.
  RawClient stranger(bridge->port(), "");
  EXPECT_NE(stranger.response().find("400"), std::string::npos) << stranger.response();
}

// config/foxglove_bridge.yaml's keys, then the flags given on top of them; a bad value in
// either, or an unknown key, is a configuration error naming the key (exit 2).
TEST_F(FoxgloveBridge, TheFileSetsTheServerAndAFlagOverridesIt) {
  const std::string config = scratch_path("foxglove_bridge.yaml");
  std::ofstream(config) << "foxglove: {client_queue_kib: 128, max_clients: 3, "
                           "slow_client_timeout_s: 2.5}\n";
  const auto bridge = start_bridge({"--config", config, "--max-clients", "5"});
  const std::string log = read_text(bridge->log());
  EXPECT_NE(log.find("(queue 128 KiB per client, a client full for 2.5 s is dropped, at most 5 "
                     "clients)"),
            std::string::npos)
      << log;
  EXPECT_EQ(bridge->child().terminate(scaled(10s), SIGINT), 0);
}

TEST(FoxgloveBridgeProcess, ABadSettingInTheFileOrAFlagIsAConfigurationError) {
  const std::string shipped = std::string(COVER_CONFIG_DIR) + "/foxglove_bridge.yaml";
  const std::string fast = scratch_path("fast.yaml");
  std::ofstream(fast) << "foxglove: {scene_rate_hz: 500}\n";
  const std::string typo = scratch_path("typo.yaml");
  std::ofstream(typo) << "foxglove: {prot: 9000}\n";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--config", fast}, "foxglove.scene_rate_hz"},
      {{"--config", typo}, "prot"},
      {{"--config", shipped, "--max-clients", "0"}, "foxglove.max_clients"},
      {{"--config", scratch_path("missing.yaml")}, "missing.yaml"}};
  for (const auto& [flags, key] : cases) {
    std::vector<std::string> argv{COVER_FOXGLOVE_BRIDGE};
    argv.insert(argv.end(), flags.begin(), flags.end());
    const Output out = run(argv, "bad.stderr");
    EXPECT_EQ(out.code, 2) << key;
    const std::string error = read_text(scratch_path("bad.stderr"));
    EXPECT_NE(error.find(key), std::string::npos) << error;
  }
}

TEST(FoxgloveBridgeProcess, HelpAndATakenPortExitAsDocumented) {
  const Output help = run({COVER_FOXGLOVE_BRIDGE, "--help"}, "help.stderr");
  EXPECT_EQ(help.code, 0);
  std::string text;
  for (const auto& l : help.lines) text += l + "\n";
  EXPECT_NE(text.find("--port"), std::string::npos);
  EXPECT_NE(text.find("Exit codes"), std::string::npos);
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  std::uint16_t port = 0;
  for (int i = 0; i < 50 && port == 0; ++i) {
    address.sin_port = htons(static_cast<std::uint16_t>(20000 + (getpid() * 13 + i * 97) % 12000));
    if (::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
      port = ntohs(address.sin_port);
    }
  }
  ASSERT_NE(port, 0);
  ASSERT_EQ(::listen(listener, 1), 0);
  auto claim = dds::DomainClaim::claim_any(160, 164);
  const Output taken = run({COVER_FOXGLOVE_BRIDGE, "--port", std::to_string(port), "--domain",
                            std::to_string(claim.domain()), "--uavs", "1", "--ugvs", "1"},
                           "taken.stderr");
  EXPECT_EQ(taken.code, 4);
  EXPECT_NE(read_text(scratch_path("taken.stderr")).find("cannot listen"), std::string::npos);
  ::close(listener);
}

}  // namespace
}  // namespace cover::test
