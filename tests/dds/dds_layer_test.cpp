#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cover/config/config_error.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "dds_test_support.hpp"

using namespace cover::dds;
using namespace std::chrono_literals;

namespace {

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::string write_temp_yaml(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Qos, NamedProfilesSetEveryPolicy) {
  const auto sensor = qos_profile("sensor");
  EXPECT_EQ(sensor.reliability, Reliability::BestEffort);
  EXPECT_EQ(sensor.durability, Durability::Volatile);
  EXPECT_EQ(sensor.history_depth, 1);
  EXPECT_GT(sensor.deadline_s, 0.0);
  const auto command = qos_profile("command");
  EXPECT_EQ(command.reliability, Reliability::Reliable);
  EXPECT_EQ(command.durability, Durability::Volatile);
  const auto state = qos_profile("state");
  EXPECT_EQ(state.reliability, Reliability::Reliable);
  EXPECT_EQ(state.durability, Durability::TransientLocal);
  EXPECT_GE(state.history_depth, 1);
}

TEST(Qos, UnknownProfileAndBadValuesAreErrors) {
  EXPECT_NE(message_of([] { qos_profile("fast"); }).find("sensor, command or state"),
            std::string::npos);
  QosProfile bad = sensor_qos();
  bad.history_depth = 0;
  EXPECT_THROW(bad.validate(), DdsError);
  bad = sensor_qos();
  bad.deadline_s = std::nan("");
  EXPECT_THROW(bad.validate(), DdsError);
}

TEST(Vendor, ParsesNamesAndRejectsOthers) {
  EXPECT_EQ(parse_vendor("fastdds"), Vendor::FastDds);
  EXPECT_EQ(parse_vendor("cyclone"), Vendor::Cyclone);
  const auto text = message_of([] { parse_vendor("opendds"); });
  EXPECT_NE(text.find("opendds"), std::string::npos);
  EXPECT_NE(text.find("fastdds or cyclone"), std::string::npos);
}

TEST(Vendor, EnvironmentChoosesTheVendorAndDomain) {
  setenv("COVER_DDS", "cyclone", 1);
  setenv("COVER_DDS_DOMAIN", "17", 1);
  const auto options = apply_environment(ParticipantOptions{});
  EXPECT_EQ(options.vendor, Vendor::Cyclone);
  EXPECT_EQ(options.domain_id, 17);
  setenv("COVER_DDS", "nonsense", 1);
  EXPECT_THROW(apply_environment(ParticipantOptions{}), DdsError);
  unsetenv("COVER_DDS");
  setenv("COVER_DDS_DOMAIN", "x1", 1);
  EXPECT_THROW(apply_environment(ParticipantOptions{}), DdsError);
  unsetenv("COVER_DDS_DOMAIN");
}

TEST(ParticipantOptionsFile, LoadsAndValidates) {
  const auto good = write_temp_yaml(
      "dds_good.yaml",
      "dds:\n  vendor: cyclone\n  domain_id: 7\n  interface: lo\n  peers: [127.0.0.1]\n");
  const auto options = ParticipantOptions::load_file(good);
  EXPECT_EQ(options.vendor, Vendor::Cyclone);
  EXPECT_EQ(options.domain_id, 7);
  ASSERT_EQ(options.peers.size(), 1u);

  const auto typo = write_temp_yaml("dds_typo.yaml", "dds:\n  domian_id: 7\n");
  EXPECT_NE(message_of([&] { ParticipantOptions::load_file(typo); }).find("domian_id"),
            std::string::npos);
  const auto bad_domain = write_temp_yaml("dds_bad.yaml", "dds:\n  domain_id: 300\n");
  EXPECT_NE(message_of([&] { ParticipantOptions::load_file(bad_domain); }).find("300"),
            std::string::npos);
  const auto bad_peer = write_temp_yaml("dds_peer.yaml", "dds:\n  peers: [not-an-ip]\n");
  EXPECT_THROW(ParticipantOptions::load_file(bad_peer), cover::config::ConfigError);
}

TEST(ParticipantOptionsFile, ShippedConfigIsValid) {
  const auto options =
      ParticipantOptions::load_file(std::string(COVER_SOURCE_DIR) + "/config/dds.yaml");
  EXPECT_NO_THROW(options.validate());
}

class OnEachVendor : public testing::TestWithParam<Vendor> {};

TEST_P(OnEachVendor, BadDomainIdIsAClearError) {
  for (int domain : {-1, 233, 100000}) {
    ParticipantOptions options;
    options.vendor = GetParam();
    options.domain_id = domain;
    const auto text = message_of([&] { Participant participant(options); });
    EXPECT_NE(text.find("domain id " + std::to_string(domain)), std::string::npos) << text;
    EXPECT_NE(text.find("0..232"), std::string::npos) << text;
  }
}

TEST_P(OnEachVendor, VendorFailureIsReportedWithTheVendorName) {
  ParticipantOptions options = cover::test::private_options(GetParam());
  options.interface_name = "no_such_if0";
  const auto text = message_of([&] { Participant participant(options); });
  ASSERT_FALSE(text.empty()) << "a participant on a missing interface must not be created";
  EXPECT_NE(text.find(GetParam() == Vendor::FastDds ? "Fast DDS" : "Cyclone DDS"),
            std::string::npos)
      << text;
}

TEST_P(OnEachVendor, PublishesAndReceivesInProcessWithBothReaderStyles) {
  ParticipantOptions options = cover::test::private_options(GetParam());
  Participant participant(options);
  const std::string topic = cover::test::private_prefix("layer") + "/status";
  std::atomic<int> callbacks{0};
  auto callback_reader = participant.make_reader<cover::msg::UavStatus>(
      topic, state_qos(), [&](const cover::msg::UavStatus&) { ++callbacks; });
  auto latest_reader = participant.make_reader<cover::msg::UavStatus>(topic, state_qos());
  auto writer = participant.make_writer<cover::msg::UavStatus>(topic, state_qos());
  ASSERT_TRUE(writer.wait_for_readers(2, 10s));
  cover::msg::UavStatus status;
  status.task_id = "t1";
  status.stage = cover::msg::Stage::STAGE_TRANSITION;
  ASSERT_TRUE(writer.write(status));
  ASSERT_TRUE(latest_reader.wait_for_sample(5s));
  ASSERT_TRUE(callback_reader.wait_for_sample(5s));
  EXPECT_EQ(latest_reader.latest()->sample, status);
  EXPECT_EQ(callbacks.load(), 1);
}

TEST_P(OnEachVendor, SensorDeadlineMissesAreCounted) {
  ParticipantOptions options = cover::test::private_options(GetParam());
  Participant participant(options);
  const std::string topic = cover::test::private_prefix("deadline") + "/imu";
  auto reader = participant.make_reader<cover::msg::UgvImu>(topic, sensor_qos());
  auto writer = participant.make_writer<cover::msg::UgvImu>(topic, sensor_qos());
  ASSERT_TRUE(writer.wait_for_readers(1, 10s));
  writer.write(cover::msg::UgvImu{});
  ASSERT_TRUE(reader.wait_for_sample(5s));
  // No further sample: the 50 ms deadline must be reported as missed.
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (reader.deadline_misses() == 0 && std::chrono::steady_clock::now() < deadline) {
    reader.wait_for_sample(10ms, reader.received_count());
  }
  EXPECT_GT(reader.deadline_misses(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Vendors, OnEachVendor, testing::Values(Vendor::FastDds, Vendor::Cyclone),
                         [](const auto& info) { return std::string(vendor_name(info.param)); });

TEST(TopicCatalog, NamesFollowTheSchemeAndResolve) {
  EXPECT_EQ(ugv_imu_topic(3), "cover/ugv/3/imu");
  EXPECT_EQ(relative_state_topic(0, 2), "cover/uav/0/rel/2");
  EXPECT_EQ(uav_command_topic(1), "cover/uav/1/cmd");
  ASSERT_NE(find_topic("cover/ugv/12/imu"), nullptr);
  EXPECT_EQ(find_topic("cover/ugv/12/imu")->type_name, "cover::idl::UgvImu");
  EXPECT_EQ(find_topic("cover/uav/0/rel/1")->type_name, "cover::idl::RelativeState");
  EXPECT_EQ(find_topic("cover/task/status")->type_name, "cover::idl::TaskStatus");
  EXPECT_EQ(find_topic("cover/ugv/x/imu"), nullptr);
  EXPECT_EQ(find_topic("cover/ugv/1/imu/extra"), nullptr);
  EXPECT_EQ(find_topic("cover/ugv//imu"), nullptr);
}

TEST(TopicCatalog, EveryEntryHasAKnownTypeAndProfileAndIsDocumented) {
  std::ifstream docs(std::string(COVER_SOURCE_DIR) + "/docs/topics.md");
  ASSERT_TRUE(docs) << "docs/topics.md is missing";
  std::stringstream text;
  text << docs.rdbuf();
  for (const auto& entry : topic_catalog()) {
    EXPECT_TRUE(cover::msg::with_type(entry.type_name, [](auto) {})) << entry.type_name;
    EXPECT_NO_THROW(qos_profile(entry.qos_profile));
    EXPECT_NE(text.str().find("`" + entry.pattern + "`"), std::string::npos)
        << entry.pattern << " is not in docs/topics.md";
    const std::string short_type = entry.type_name.substr(entry.type_name.rfind(':') + 1);
    EXPECT_NE(text.str().find(short_type), std::string::npos);
  }
}

// The field configuration (no multicast, static unicast peers) on loopback, across vendors.
class UnicastPeers : public testing::TestWithParam<std::pair<Vendor, Vendor>> {};

TEST_P(UnicastPeers, DiscoverEachOtherWithoutMulticast) {
  ParticipantOptions writer_options = cover::test::private_options(GetParam().first);
  writer_options.peers = {"127.0.0.1"};
  ParticipantOptions reader_options = writer_options;
  reader_options.vendor = GetParam().second;
  Participant writer_side(writer_options);
  Participant reader_side(reader_options);
  const std::string topic = cover::test::private_prefix("peers") + "/task";
  auto reader = reader_side.make_reader<cover::msg::TaskStatus>(topic, state_qos());
  auto writer = writer_side.make_writer<cover::msg::TaskStatus>(topic, state_qos());
  ASSERT_TRUE(writer.wait_for_readers(1, 30s));
  cover::msg::TaskStatus status;
  status.task_id = "peers";
  status.state = cover::msg::TaskState::TASK_RUNNING;
  ASSERT_TRUE(writer.write(status));
  ASSERT_TRUE(reader.wait_for_sample(10s));
  EXPECT_EQ(reader.latest()->sample, status);
}

INSTANTIATE_TEST_SUITE_P(VendorPairs, UnicastPeers,
                         testing::Values(std::pair{Vendor::FastDds, Vendor::Cyclone},
                                         std::pair{Vendor::Cyclone, Vendor::FastDds}),
                         [](const auto& info) {
                           return std::string(vendor_name(info.param.first)) + "_to_" +
                                  vendor_name(info.param.second);
                         });

}  // namespace
