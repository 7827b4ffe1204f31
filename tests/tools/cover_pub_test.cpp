// `cover pub` standing in for an agent: ros2's stamping conventions ("stamp_ns": "now",
// "seq": "auto") give every sample its own send time and count, as a receiver that checks
// stamps (a flight-controller bridge) needs. A subscriber in the test receives them.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <string>
#include <vector>

#include "cover/clock/clock.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace {

using namespace std::chrono_literals;

using cover::test::scaled;

// Everything `cover ARGS` printed on stdout, and its exit code.
std::pair<int, std::string> run_cover(std::vector<std::string> args) {
  args.insert(args.begin(), COVER_CLI);
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = cover::test::scratch_path("cover.stderr");
  cover::process::ChildProcess cover(args, options);
  std::string out;
  while (const auto line = cover.read_line(scaled(30s))) out += *line + "\n";
  return {cover.wait(scaled(30s)).value_or(-1), out};
}

TEST(CoverPub, NowAndAutoStampEverySampleWithItsSendTimeAndCount) {
  const auto claim = cover::dds::DomainClaim::claim(210, std::chrono::minutes(10));
  cover::dds::ParticipantOptions options;
  options.vendor = cover::dds::Vendor::Cyclone;
  options.domain_id = claim.domain();
  cover::dds::Participant participant(options);
  std::mutex mutex;
  std::condition_variable arrived;
  std::vector<cover::msg::UavCommand> received;
  auto reader = participant.make_reader(cover::dds::topics::uav_command(0),
                                        [&](const cover::msg::UavCommand& command) {
                                          std::lock_guard<std::mutex> lock(mutex);
                                          received.push_back(command);
                                          arrived.notify_all();
                                        });
  const std::int64_t before_ns = cover::clock::system_ns();
  const auto [code, out] =
      run_cover({"pub", "cover/uav/0/cmd",
                 R"({"uav_id": 0, "stamp_ns": "now", "seq": "auto:5", "measurement_stamp_ns": "now",
           "thrust_m_s2": 9.81, "armed": true})",
                 "--rate", "50", "--count", "10", "--wait", "20", "--dds", "fastdds", "--domain",
                 std::to_string(claim.domain())});
  const std::int64_t after_ns = cover::clock::system_ns();
  ASSERT_EQ(code, 0) << out;

  // Reliable, depth 1: a sample may be overwritten on the way (the first too, when the
  // second is written before the reader acknowledged it), never reordered. `cover pub`
  // waits for acknowledgments before it exits, so the tenth, seq 14, always arrives.
  constexpr std::uint32_t kFirstSeq = 5;
  constexpr std::uint32_t kLastSeq = kFirstSeq + 9;
  std::unique_lock<std::mutex> lock(mutex);
  ASSERT_TRUE(arrived.wait_for(
      lock, scaled(5s), [&] { return !received.empty() && received.back().seq == kLastSeq; }))
      << received.size() << " samples, none with seq " << kLastSeq;
  ASSERT_GE(received.size(), 5u);
  std::int64_t last_stamp_ns = 0;
  std::int64_t last_seq = kFirstSeq - 1;
  for (const auto& command : received) {
    EXPECT_GT(command.stamp_ns, last_stamp_ns);
    EXPECT_GE(command.stamp_ns, before_ns);
    EXPECT_LE(command.stamp_ns, after_ns);
    EXPECT_EQ(command.measurement_stamp_ns, command.stamp_ns) << "one send time per sample";
    EXPECT_GT(static_cast<std::int64_t>(command.seq), last_seq);
    EXPECT_DOUBLE_EQ(command.thrust_m_s2, 9.81);
    EXPECT_TRUE(command.armed);
    last_stamp_ns = command.stamp_ns;
    last_seq = command.seq;
  }
  // Ten samples from the given start end at its ninth successor, not at 9 or 10.
  EXPECT_EQ(last_seq, kLastSeq) << "counts from the given start";
  // 10 samples at 50 Hz: the first and the last were sent ~180 ms apart, not at once.
  if (received.size() == 10) {
    EXPECT_GT(received.back().stamp_ns - received.front().stamp_ns, 100'000'000);
  }
}

TEST(CoverPub, HelpExplainsTheConventionsAndABadSeqIsAnError) {
  const auto [bad_code, bad_out] = run_cover(
      {"pub", "cover/uav/0/cmd", R"({"seq": "auto:x"})", "--wait", "0", "--domain", "210"});
  EXPECT_EQ(bad_code, 2);
  const auto [help_code, help] = run_cover({"pub", "--help"});
  EXPECT_EQ(help_code, 0);
  for (const char* part : {"\"stamp_ns\": \"now\"", "\"seq\": \"auto\"", "auto:N", "stale"}) {
    EXPECT_NE(help.find(part), std::string::npos) << part << " not in:\n" << help;
  }
}

}  // namespace
