// `cover record` as a user runs it, checked by independent readers: samples published here
// on several topics (nested structs, sequences, strings, enums, 64-bit stamps) are read back
// by @mcap/core's indexed reader and decoded by @foxglove/omgidl-serialization from the
// schema stored in the file, to exactly the published values. A recorder killed with
// SIGKILL leaves a file the stream reader opens with every sample older than a chunk's
// duration. Skips only when Node is absent.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "published_samples.hpp"
#include "recorder_support.hpp"

namespace cover::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const fs::path kPeerDir = COVER_MCAP_PEER_DIR;

class Recording : public ::testing::Test {
 protected:
  void SetUp() override {
    node_ = find_node();
    if (node_.empty()) GTEST_SKIP() << "node is not installed: the MCAP reader tests need Node";
    ASSERT_TRUE(fs::exists(kPeerDir / "node_modules" / "@mcap" / "core" / "package.json"))
        << "the MCAP readers are not installed in " << kPeerDir
        << ": run scripts/setup (npm ci --prefix tests/mcap/peer)";
    claim_.emplace(dds::DomainClaim::claim_any(195, 199));
    dds::ParticipantOptions options;
    options.vendor = dds::Vendor::Cyclone;  // the recorder runs Fast DDS: across vendors
    options.domain_id = claim_->domain();
    participant_.emplace(options);
  }

  std::vector<std::string> recorder_args(const std::string& file,
                                         const std::vector<std::string>& extra) const {
    std::vector<std::string> args{
        COVER_CLI, "record", "-o",    file,      "--uavs",   "1",
        "--ugvs",  "2",      "--dds", "fastdds", "--domain", std::to_string(claim_->domain())};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }

  // The decoded messages (JSON objects), then the summary line.
  std::vector<nlohmann::json> read_with_node(const std::string& file, const std::string& mode) {
    const Output out = run({node_, (kPeerDir / "read_mcap.js").string(), file, mode},
                           "read_mcap_" + mode + ".stderr");
    EXPECT_EQ(out.code, 0) << "read_mcap.js failed: see "
                           << scratch_path("read_mcap_" + mode + ".stderr");
    std::vector<nlohmann::json> lines;
    for (const auto& line : out.lines) lines.push_back(nlohmann::json::parse(line));
    return lines;
  }

  // A reader's match is not visible to its writer's side: a reliable sample written before
  // the recorder's reader knows the writer is not delivered. Publishes warm-up samples
  // (stamped 1, 2, ... ns: below kWarmUpEndNs, left out of the checks) until the file holds
  // `topics` topics, so every reader of the recorder has received from its writer.
  void warm_up(const std::string& file, std::size_t topics,
               const std::function<void(std::int64_t)>& publish) {
    std::int64_t n = 0;
    const bool every_topic = wait_until(
        [&] {
          publish(++n);
          const Output info =
              run({COVER_CLI, "bag", "info", file, "--json"}, "bag_info_warm.stderr");
          return !info.lines.empty() &&
                 nlohmann::json::parse(info.lines[0])["topics"].size() == topics;
        },
        30s, 20ms);
    ASSERT_TRUE(every_topic) << "the recorder wrote no sample of every topic within the deadline";
  }

  std::string node_;
  std::optional<dds::DomainClaim> claim_;
  std::optional<dds::Participant> participant_;
};

constexpr std::int64_t kWarmUpEndNs = 1'000'000'000;

template <typename T>
bool wait_matched(dds::Writer<T>& writer) {
  return writer.wait_for_readers(1, scaled(20s));
}

TEST_F(Recording, EverySampleDecodesInTheIndependentReadersToThePublishedValues) {
  for (const std::string compression : {"zstd", "lz4", "none"}) {
    SCOPED_TRACE(compression);
    const std::string file = scratch_path("flight_" + compression + ".mcap");
    process::SpawnOptions options;
    options.log_file = scratch_path("record_" + compression + ".log");
    process::ChildProcess recorder(
        recorder_args(file, {"--compression", compression, "--chunk-duration", "0.05"}), options);

    auto imu = participant_->make_writer(dds::topics::ugv_imu(1));
    auto reference = participant_->make_writer(dds::topics::uav_reference(0));
    auto task = participant_->make_writer(dds::topics::task_request());
    ASSERT_TRUE(wait_matched(imu) && wait_matched(reference) && wait_matched(task));
    warm_up(file, 3, [&](std::int64_t stamp_ns) {
      imu.write(warm(imu_sample(0), stamp_ns));
      reference.write(warm(reference_sample(0, 3), stamp_ns));
      task.write(warm(task_sample(0), stamp_ns));
    });

    std::map<std::string, nlohmann::json> published;  // by topic + stamp
    constexpr std::uint32_t kSamples = 60;
    for (std::uint32_t i = 0; i < kSamples; ++i) {
      imu.write(imu_sample(i));
      reference.write(reference_sample(i, 3 + i));
      task.write(task_sample(i));
      published["imu" + std::to_string(imu_sample(i).stamp_ns)] = decoded_form(imu_sample(i));
      published["ref" + std::to_string(reference_sample(i, 3 + i).stamp_ns)] =
          decoded_form(reference_sample(i, 3 + i));
      published["task" + std::to_string(task_sample(i).stamp_ns)] = decoded_form(task_sample(i));
      std::this_thread::sleep_for(2ms);  // pacing a 500 Hz publisher, not synchronisation
    }
    ASSERT_TRUE(reference.wait_for_acknowledgments(scaled(10s)));
    ASSERT_TRUE(task.wait_for_acknowledgments(scaled(10s)));
    EXPECT_EQ(recorder.terminate(scaled(20s), SIGINT), 0) << "see " << options.log_file;

    const auto lines = read_with_node(file, "indexed");
    ASSERT_FALSE(lines.empty());
    const auto& summary = lines.back();
    ASSERT_TRUE(summary.value("summary", false)) << summary.dump();
    EXPECT_EQ(summary["compressions"],
              nlohmann::json::array({compression == "none" ? "" : compression}));
    std::map<std::string, int> counts;
    for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
      const auto& m = lines[i];
      const std::string topic = m["topic"];
      const std::string prefix = topic == "cover/ugv/1/imu"         ? "imu"
                                 : topic == "cover/uav/0/reference" ? "ref"
                                                                    : "task";
      const auto expected = published.find(prefix + m["value"]["stamp_ns"].get<std::string>());
      if (std::stoll(m["value"]["stamp_ns"].get<std::string>()) < kWarmUpEndNs) continue;
      ASSERT_NE(expected, published.end()) << m.dump();
      EXPECT_EQ(m["value"], expected->second) << topic;
      EXPECT_EQ(m["publish_time"], m["value"]["stamp_ns"]) << "publish time = the DDS stamp";
      ++counts[prefix];
    }
    // Reliable topics arrive whole; the IMU is best effort (sensor QoS), nearly whole here.
    EXPECT_EQ(counts["ref"], static_cast<int>(kSamples));
    EXPECT_EQ(counts["task"], static_cast<int>(kSamples));
    EXPECT_GE(counts["imu"], static_cast<int>(kSamples) * 9 / 10);
    EXPECT_EQ(summary["statistics_message_count"], lines.size() - 1);

    // Our own `cover bag info --json` agrees with the independent reader.
    const Output info = run({COVER_CLI, "bag", "info", file, "--json"}, "bag_info.stderr");
    ASSERT_EQ(info.code, 0);
    const auto bag = nlohmann::json::parse(info.lines.at(0));
    EXPECT_EQ(bag["message_count"], summary["statistics_message_count"]);
    EXPECT_TRUE(bag["closed"].get<bool>());
    EXPECT_EQ(bag["topics"].size(), 3U);
  }
}

TEST_F(Recording, AKilledRecorderLeavesAFileTheStreamReaderOpensWithAllButItsLastChunk) {
  const std::string file = scratch_path("killed.mcap");
  process::SpawnOptions options;
  options.log_file = scratch_path("record_killed.log");
  process::ChildProcess recorder(recorder_args(file, {"--chunk-duration", "0.2"}), options);
  auto task = participant_->make_writer(dds::topics::task_request());
  ASSERT_TRUE(wait_matched(task));
  warm_up(file, 1, [&](std::int64_t stamp_ns) { task.write(warm(task_sample(0), stamp_ns)); });
  constexpr std::uint32_t kSamples = 40;
  for (std::uint32_t i = 0; i < kSamples; ++i) task.write(task_sample(i));
  ASSERT_TRUE(task.wait_for_acknowledgments(scaled(10s)));
  // Every sample is on disk once the recorder has closed the chunk holding it (0.2 s after
  // its first sample): wait for the last one, then kill the recorder before its summary.
  const std::string last_stamp = std::to_string(task_sample(kSamples - 1).stamp_ns);
  wait_until(
      [&] {
        const auto lines = read_with_node(file, "stream");
        return lines.size() >= 2 && lines[lines.size() - 2]["value"]["stamp_ns"] == last_stamp;
      },
      20s, 50ms);
  EXPECT_EQ(recorder.terminate(scaled(5s), SIGKILL), 128 + SIGKILL);

  const auto lines = read_with_node(file, "stream");
  ASSERT_GE(lines.size(), kSamples + 1U);
  EXPECT_FALSE(lines.back()["done"].get<bool>()) << "no footer: the stream is unfinished";
  std::uint32_t next = 0;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    if (std::stoll(lines[i]["value"]["stamp_ns"].get<std::string>()) < kWarmUpEndNs) continue;
    ASSERT_LT(next, kSamples);
    EXPECT_EQ(lines[i]["value"], decoded_form(task_sample(next++)));
  }
  EXPECT_EQ(next, kSamples) << "every sample older than a chunk's duration is in the file";
  const Output info = run({COVER_CLI, "bag", "info", file}, "bag_info_killed.stderr");
  EXPECT_EQ(info.code, 1) << "a cut file is reported as damaged";
  std::string text;
  for (const auto& line : info.lines) text += line + "\n";
  EXPECT_NE(text.find("Closed:            NO"), std::string::npos) << text;
  EXPECT_NE(text.find("without its summary and Footer"), std::string::npos) << text;
}

}  // namespace
}  // namespace cover::test
