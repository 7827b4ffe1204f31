// `cover play` and `cover bag info` on files made here with the MCAP writer and the CDR
// codec: play republishes every sample at the recorded pace (scaled by --rate, from
// --start, only --topics); a cut, corrupt or foreign file is reported with where and what
// (byte offset), what is readable still played, and nothing crashes.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cover/dds/cdr_codec.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/mcap/writer.hpp"
#include "cover/msg/idl_schema.hpp"
#include "cover/test/file_contents.hpp"
#include "recorder_support.hpp"

namespace cover::test {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr std::uint32_t kSamples = 50;
constexpr std::uint64_t kPeriodNs = 20'000'000;  // recorded 20 ms apart: 0.98 s in all

msg::TransitionTask task(std::uint32_t i) {
  msg::TransitionTask t;
  t.task_id = "played-" + std::to_string(i);
  t.uav_id = 0;
  t.stamp_ns = 1'000'000'000 + i;
  t.processes.resize(i % 2);
  return t;
}

// A recording of kSamples tasks on cover/task/request, as cover record writes it.
void write_recording(const std::string& path) {
  mcap::WriterOptions options;
  options.chunk_size_bytes = 1024;  // several chunks, so a cut leaves some whole
  mcap::Writer writer(path, options);
  const auto schema =
      writer.add_schema(msg::TransitionTask::kTypeName, "omgidl",
                        std::string(msg::idl_schema(msg::TransitionTask::kTypeName)));
  const auto channel = writer.add_channel(schema, "cover/task/request", "cdr");
  dds::CdrCodec codec(dds::type_support<msg::TransitionTask>());
  std::vector<std::uint8_t> bytes;
  for (std::uint32_t i = 0; i < kSamples; ++i) {
    ASSERT_TRUE(codec.serialize(task(i), bytes));
    const std::uint64_t log_ns = 1'700'000'000'000'000'000ULL + i * kPeriodNs;
    ASSERT_TRUE(writer.write({channel, i, log_ns, static_cast<std::uint64_t>(task(i).stamp_ns)},
                             bytes.data(), bytes.size()));
  }
  ASSERT_TRUE(writer.close());
}

std::string joined(const Output& out) {
  std::string text;
  for (const auto& line : out.lines) text += line + "\n";
  return text;
}

// play's --delay, the wait for discovery before the first sample: discovery took over
// 2 s on a loaded CI machine, and a sample written before the reader knows its writer is
// lost.
std::string discovery_s() {
  return std::to_string(scaled(std::chrono::milliseconds(5000)).count() / 1000);
}

class Play : public ::testing::Test {
 protected:
  void SetUp() override {
    claim_.emplace(dds::DomainClaim::claim_any(195, 199));
    dds::ParticipantOptions options;
    // The player's vendor: across vendors discovery takes ~2 s, the player's --delay 2
    // would be too short on a loaded machine (a reliable sample written before the reader
    // knows its writer is lost).
    options.vendor = dds::Vendor::FastDds;
    options.domain_id = claim_->domain();
    participant_.emplace(options);
    reader_ = participant_->make_reader(dds::topics::task_request(),
                                        [this](const msg::TransitionTask& t) {
                                          std::lock_guard<std::mutex> lock(mutex_);
                                          received_.push_back(t);
                                          times_.push_back(Clock::now());
                                        });
    file_ = scratch_path("tasks.mcap");
    write_recording(file_);
  }

  Output play(const std::string& file, std::vector<std::string> extra) {
    std::vector<std::string> args{
        COVER_CLI, "play", file, "--dds", "fastdds", "--domain", std::to_string(claim_->domain())};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args, "play.stderr");
  }

  // Waits until `count` samples arrived (play returns once it has written them).
  std::size_t wait_received(std::size_t count) {
    const auto deadline = Clock::now() + scaled(10s);
    while (Clock::now() < deadline) {
      if (reader_.received_count() >= count) break;
      reader_.wait_for_sample(100ms, reader_.received_count());
    }
    std::lock_guard<std::mutex> lock(mutex_);
    return received_.size();
  }

  std::optional<dds::DomainClaim> claim_;
  std::optional<dds::Participant> participant_;
  dds::Reader<msg::TransitionTask> reader_;
  std::mutex mutex_;
  std::vector<msg::TransitionTask> received_;
  std::vector<Clock::time_point> times_;
  std::string file_;
};

TEST_F(Play, RepublishesEverySampleAtTheRecordedPaceScaledByRate) {
  const Output out = play(file_, {"--rate", "2", "--delay", discovery_s()});
  ASSERT_EQ(out.code, 0) << read_text(scratch_path("play.stderr"));
  ASSERT_EQ(wait_received(kSamples), kSamples);
  std::lock_guard<std::mutex> lock(mutex_);
  for (std::uint32_t i = 0; i < kSamples; ++i) EXPECT_EQ(received_[i], task(i));
  // 0.98 s recorded, played twice as fast: 0.49 s. Never faster; slower only under load.
  const double span_s = std::chrono::duration<double>(times_.back() - times_.front()).count();
  EXPECT_GE(span_s, 0.45);
  EXPECT_LE(span_s, 0.49 + 1.0 * scaled(1000ms).count() / 1000.0);
}

TEST_F(Play, StartSkipsTheFirstSecondsAndTopicsSelects) {
  Output out = play(file_, {"--rate", "4", "--start", "0.5", "--delay", discovery_s()});
  ASSERT_EQ(out.code, 0);
  ASSERT_EQ(wait_received(kSamples / 2), kSamples / 2);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    EXPECT_EQ(received_.front(), task(kSamples / 2));  // 25 * 20 ms = 0.5 s in
    received_.clear();
  }
  out = play(file_, {"--topics", "cover/uav/*", "--delay", "0"});
  EXPECT_EQ(out.code, 0);
  EXPECT_NE(read_text(scratch_path("play.stderr")).find("published 0 samples"), std::string::npos);
}

TEST_F(Play, ACutFileIsReportedWhereAndWhatAndItsReadablePartPlayed) {
  const auto whole = read_bytes(file_);
  const std::string cut = scratch_path("cut.mcap");
  write_bytes(cut, {whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(whole.size() / 2)});

  const Output info = run({COVER_CLI, "bag", "info", cut}, "info.stderr");
  EXPECT_EQ(info.code, 1);
  const std::string text = joined(info);
  EXPECT_NE(text.find("Closed:            NO"), std::string::npos) << text;
  EXPECT_NE(text.find("Problem:           at byte "), std::string::npos) << text;
  EXPECT_NE(text.find("truncated"), std::string::npos) << text;

  const Output out = play(cut, {"--rate", "10", "--delay", discovery_s()});
  EXPECT_EQ(out.code, 1);
  const std::string log = read_text(scratch_path("play.stderr"));
  EXPECT_NE(log.find(cut + ": at byte "), std::string::npos) << log;
  const std::size_t played = wait_received(1);
  EXPECT_GT(played, 5U);
  EXPECT_LT(played, kSamples);
}

TEST_F(Play, CorruptAndForeignFilesAreReportedNeverACrash) {
  auto bytes = read_bytes(file_);
  const std::string corrupt = scratch_path("corrupt.mcap");
  bytes[bytes.size() / 3] ^= 0x40;  // inside a chunk's records
  bytes[bytes.size() / 3 + 1] ^= 0x11;
  write_bytes(corrupt, bytes);
  const Output info = run({COVER_CLI, "bag", "info", corrupt, "--json"}, "info.stderr");
  EXPECT_EQ(info.code, 1);
  const auto json = nlohmann::json::parse(info.lines.at(0));
  ASSERT_FALSE(json["issues"].empty());
  EXPECT_GT(json["issues"][0]["offset"].get<std::uint64_t>(), 0U);
  EXPECT_LE(json["message_count"].get<std::uint64_t>(), kSamples);
  EXPECT_EQ(play(corrupt, {"--rate", "20", "--delay", "0"}).code, 1);

  const std::string foreign = scratch_path("foreign.mcap");
  write_bytes(foreign, {'#', '!', '/', 'b', 'i', 'n', '/', 's', 'h', '\n'});
  const Output foreign_info = run({COVER_CLI, "bag", "info", foreign}, "info.stderr");
  EXPECT_EQ(foreign_info.code, 2);
  EXPECT_NE(joined(foreign_info).find("not an MCAP file"), std::string::npos);
  EXPECT_EQ(play(foreign, {}).code, 2);
  EXPECT_EQ(run({COVER_CLI, "bag", "info", scratch_path("missing.mcap")}, "info.stderr").code, 2);
}

}  // namespace
}  // namespace cover::test
