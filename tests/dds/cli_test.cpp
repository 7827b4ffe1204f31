// The ground-station CLI as a user runs it: `cover pub` in one process, `cover echo` in
// another, on every vendor pair.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cover/process/child_process.hpp"
#include "dds_test_support.hpp"

using namespace std::chrono_literals;

namespace {

struct Pair {
  const char* publisher;
  const char* subscriber;
};

class CoverCli : public testing::TestWithParam<Pair> {};

TEST_P(CoverCli, EchoOnOneVendorReceivesPubOnTheOther) {
  const std::string domain = std::to_string(cover::test::private_domain_id());
  cover::process::ChildProcess echo(
      {COVER_CLI, "echo", "cover/uav/3/status", "--count", "1", "--json", "--timeout", "30",
       "--dds", GetParam().subscriber, "--domain", domain},
      {}, /*capture_stdout=*/true);
  cover::process::ChildProcess pub({COVER_CLI, "pub", "cover/uav/3/status",
                                    R"({"uav_id": 3, "task_id": "cli", "stage": "STAGE_FINAL",
                                        "solve_time_us": 81.25})",
                                    "--dds", GetParam().publisher, "--domain", domain, "--wait",
                                    "20"});
  const auto line = echo.read_line(30s);
  ASSERT_TRUE(line.has_value()) << "cover echo printed nothing";
  const auto sample = nlohmann::json::parse(*line);
  EXPECT_EQ(sample["uav_id"], 3);
  EXPECT_EQ(sample["task_id"], "cli");
  EXPECT_EQ(sample["stage"], "STAGE_FINAL");
  EXPECT_EQ(sample["solve_time_us"], 81.25);
  EXPECT_EQ(sample["armed"], false);  // left out: zero value
  EXPECT_EQ(echo.wait(10s), 0);
  EXPECT_EQ(pub.wait(10s), 0);
}

INSTANTIATE_TEST_SUITE_P(VendorPairs, CoverCli,
                         testing::Values(Pair{"fastdds", "cyclone"}, Pair{"cyclone", "fastdds"},
                                         Pair{"fastdds", "fastdds"}, Pair{"cyclone", "cyclone"}),
                         [](const auto& info) {
                           return std::string(info.param.publisher) + "_to_" +
                                  info.param.subscriber;
                         });

TEST(CoverCliErrors, UnknownFieldTopicAndDomainAreClearErrors) {
  cover::process::ChildProcess bad_field(
      {COVER_CLI, "pub", "cover/uav/0/cmd", R"({"thrust": 9.8})", "--wait", "0"});
  EXPECT_EQ(bad_field.wait(20s), 2);
  cover::process::ChildProcess bad_topic({COVER_CLI, "echo", "cover/uav/x/cmd"});
  EXPECT_EQ(bad_topic.wait(20s), 2);
  cover::process::ChildProcess bad_domain(
      {COVER_CLI, "echo", "cover/uav/0/cmd", "--domain", "400"});
  EXPECT_EQ(bad_domain.wait(20s), 2);
  cover::process::ChildProcess bad_vendor({COVER_CLI, "topics"}, {"COVER_DDS=opendds"});
  EXPECT_EQ(bad_vendor.wait(20s), 0) << "`cover topics` needs no DDS";
}

}  // namespace
