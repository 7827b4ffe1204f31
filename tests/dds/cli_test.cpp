// The ground-station CLI as a user runs it: `cover pub` in one process, `cover echo` in
// another, on every vendor pair.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

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

// The lines of docs/topics.md's topic table, header included.
std::vector<std::string> documented_table() {
  std::ifstream docs(std::string(COVER_SOURCE_DIR) + "/docs/topics.md");
  std::vector<std::string> table;
  std::string line;
  while (std::getline(docs, line)) {
    if (table.empty() && line.rfind("| topic | type |", 0) != 0) continue;
    if (line.rfind("|", 0) != 0) break;
    table.push_back(line);
  }
  return table;
}

std::vector<std::string> output_lines(const std::vector<std::string>& argv) {
  cover::process::ChildProcess child(argv, {}, /*capture_stdout=*/true);
  std::vector<std::string> lines;
  while (auto line = child.read_line(20s)) lines.push_back(*line);
  EXPECT_EQ(child.wait(20s), 0);
  return lines;
}

TEST(CoverCliTopics, MarkdownIsTheTableOfTheDocs) {
  const auto documented = documented_table();
  ASSERT_GT(documented.size(), 2u) << "no topic table in docs/topics.md";
  EXPECT_EQ(output_lines({COVER_CLI, "topics", "--markdown"}), documented)
      << "regenerate the table in docs/topics.md with `cover topics --markdown`";
}

TEST(CoverCliTopics, JsonAndTableListEveryTopic) {
  const auto rows = documented_table().size() - 2;
  const auto json = output_lines({COVER_CLI, "topics", "--json"});
  ASSERT_EQ(json.size(), rows);
  const auto first = nlohmann::json::parse(json.front());
  EXPECT_EQ(first["topic"], "cover/ugv/<k>/imu");
  EXPECT_EQ(first["type"], "cover::idl::UgvImu");
  EXPECT_EQ(first["qos"], "sensor");
  EXPECT_TRUE(first.contains("publisher_subscribers"));
  EXPECT_EQ(output_lines({COVER_CLI, "topics"}).size(), 2 * rows);  // entry + description
}

}  // namespace
