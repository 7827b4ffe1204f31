// `cover record` subscribes to a topic when its first writer appears, as `ros2 bag record
// -a` does: a writer that was there before the recorder started and one made after it are
// both recorded, and nothing else of the fleet's 78 topics gets a reader (each one Fast DDS
// would check on every sample it receives). Its log says when it took each topic.
#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "recorder_support.hpp"

namespace cover::test {
namespace {

using namespace std::chrono_literals;

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The topics `file` holds so far (`cover bag info --json`), 0 while it has no summary yet.
std::size_t topics_in(const std::string& file) {
  const Output info = run({COVER_CLI, "bag", "info", file, "--json"}, "bag_info_discovery.stderr");
  if (info.lines.empty()) return 0;
  const auto summary = nlohmann::json::parse(info.lines[0], nullptr, false);
  return summary.is_object() ? summary["topics"].size() : 0;
}

TEST(RecorderDiscovery, SubscribesEachTopicWhenItsFirstWriterAppears) {
  const auto claim = dds::DomainClaim::claim_any(195, 199);
  dds::ParticipantOptions options;
  options.vendor = dds::Vendor::Cyclone;  // the recorder runs Fast DDS: across vendors
  options.domain_id = claim.domain();
  dds::Participant fleet(options);
  auto before = fleet.make_writer(dds::topics::ugv_imu(5));

  const std::string file = scratch_path("discovery.mcap");
  process::SpawnOptions spawn;
  spawn.log_file = scratch_path("record_discovery.log");
  // The whole fleet's topics (4 UAVs, 8 UGVs) are eligible; only two will have writers.
  process::ChildProcess recorder({COVER_CLI, "record", "-o", file, "--chunk-duration", "0.05",
                                  "--dds", "fastdds", "--domain", std::to_string(claim.domain())},
                                 spawn);
  auto after = fleet.make_writer(dds::topics::uav_status(3));
  std::int64_t stamp_ns = 0;
  const bool both = wait_until(
      [&] {
        msg::UgvImu imu;
        imu.ugv_id = 5;
        imu.stamp_ns = ++stamp_ns;
        before.write(imu);
        msg::UavStatus status;
        status.uav_id = 3;
        status.stamp_ns = stamp_ns;
        after.write(status);
        return topics_in(file) == 2;
      },
      30s, 20ms);
  ASSERT_TRUE(both) << "the recorder did not record both writers' topics; see " << spawn.log_file;
  EXPECT_EQ(recorder.terminate(scaled(20s), SIGINT), 0) << "see " << spawn.log_file;

  const std::string log = file_text(spawn.log_file);
  EXPECT_NE(log.find("recording cover/ugv/5/imu (cover::idl::UgvImu): its first writer appeared"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("recording cover/uav/3/status (cover::idl::UavStatus): its first writer "
                     "appeared"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("of 2 topics (2 subscribed)"), std::string::npos)
      << "a reader for a topic nobody published:\n"
      << log;
}

}  // namespace
}  // namespace cover::test
