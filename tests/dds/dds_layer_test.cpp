#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "dds_test_support.hpp"

using namespace cover::dds;
using namespace std::chrono_literals;
namespace msg = cover::msg;

namespace {

using cover::test::message_of;
using cover::test::write_temp_yaml;

// A thread woken by a sample (Reader::wait_for_sample) reads what the reader's callback
// made of it: the callback runs before the sample is counted.
TEST(Reader, TheCallbackRunsBeforeTheSampleCountsSoAWokenWaiterFindsItsWork) {
  using State = cover::dds::Reader<cover::msg::UgvImu>::State;
  std::optional<std::uint64_t> count_during_callback;
  std::shared_ptr<State> state;
  state = std::make_shared<State>(
      [&](const cover::msg::UgvImu&) { count_during_callback = state->count(); });
  state->deliver(cover::msg::UgvImu{});
  EXPECT_EQ(count_during_callback, std::optional<std::uint64_t>(0));
  EXPECT_EQ(state->count(), 1u);
  EXPECT_TRUE(state->wait_beyond(0, std::chrono::milliseconds(0)));
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
  EXPECT_NE(
      message_of([] { qos_profile("fast"); }).find("sensor, command, state, request or exchange"),
      std::string::npos);
  QosProfile bad = sensor_qos();
  bad.history_depth = 0;
  EXPECT_THROW(bad.validate(), DdsError);
  bad = sensor_qos();
  bad.deadline_s = std::nan("");
  EXPECT_THROW(bad.validate(), DdsError);
  for (const double delay_s : {-0.01, 1.5, std::nan("")}) {
    bad = command_qos();
    bad.acknowledgement_delay_s = delay_s;
    EXPECT_THROW(bad.validate(), DdsError) << delay_s;
  }
  bad = command_qos();
  bad.acknowledgement_delay_s = 0.05;
  EXPECT_NO_THROW(bad.validate());
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

// The ports an announcement goes to per unicast peer: a port pair per participant of one
// domain's range.
TEST(ParticipantOptionsFile, ParticipantsPerPeerIsBounded) {
  for (const char* bad : {"0", "121", "-3"}) {
    const auto file = write_temp_yaml(std::string("dds_range_") + bad + ".yaml",
                                      std::string("dds:\n  participants_per_peer: ") + bad + "\n");
    const std::string text = message_of([&] { ParticipantOptions::load_file(file); });
    EXPECT_NE(text.find("participants_per_peer"), std::string::npos) << bad << ": " << text;
  }
  const auto good = write_temp_yaml("dds_range_8.yaml", "dds:\n  participants_per_peer: 8\n");
  EXPECT_EQ(ParticipantOptions::load_file(good).participants_per_peer, 8);
  EXPECT_EQ(ParticipantOptions{}.participants_per_peer, 72);
}

TEST(ParticipantOptionsFile, ShippedConfigIsValid) {
  const auto options =
      ParticipantOptions::load_file(std::string(COVER_SOURCE_DIR) + "/config/dds.yaml");
  EXPECT_NO_THROW(options.validate());
}

// A process joining a running system (a recorder, `cover echo`) learns each participant
// that missed answering its first announcement at that participant's next one: every
// shipped process announces at least twice a second, so a late joiner knows the whole
// system within about half a second (Fast DDS's default, 3 s, gave a recorder its first
// sample up to 3.3 s after it started).
TEST(ParticipantOptionsFile, ShippedConfigAnnouncesOftenEnoughForALateJoiner) {
  const auto options =
      ParticipantOptions::load_file(std::string(COVER_SOURCE_DIR) + "/config/dds.yaml");
  EXPECT_GT(options.announcement_period_s, 0.0) << "0 is the vendor's default: Fast DDS 3 s";
  EXPECT_LE(options.announcement_period_s, 0.5);
}

TEST(ParticipantOptionsFile, ProfileReplacesTheNetworkKeys) {
  const auto file = write_temp_yaml(
      "dds_profiles.yaml",
      "dds:\n  domain_id: 4\n  interface: lo\n  profiles:\n    wifi:\n      interface: wifi0\n"
      "      peers: [10.0.0.2]\n      announcement_period_s: 0.5\n    spare: {}\n");
  const auto plain = ParticipantOptions::load_file(file);
  EXPECT_EQ(plain.interface_name, "lo");
  EXPECT_TRUE(plain.peers.empty());
  const auto wifi = ParticipantOptions::load_file(file, "wifi");
  EXPECT_EQ(wifi.interface_name, "wifi0");
  ASSERT_EQ(wifi.peers.size(), 1u);
  EXPECT_DOUBLE_EQ(wifi.announcement_period_s, 0.5);
  EXPECT_EQ(wifi.domain_id, 4);  // not a network key: stays
  EXPECT_NE(message_of([&] { ParticipantOptions::load_file(file, "wfi"); }).find("spare"),
            std::string::npos);  // names the known profiles
  const auto typo = write_temp_yaml("dds_profile_typo.yaml",
                                    "dds:\n  profiles:\n    other:\n      peer: [10.0.0.2]\n");
  EXPECT_NE(message_of([&] { ParticipantOptions::load_file(typo); }).find("peer"),
            std::string::npos);  // a typo in an unselected profile fails too
  const auto bad_period =
      write_temp_yaml("dds_bad_period.yaml", "dds:\n  announcement_period_s: -1\n");
  EXPECT_NE(
      message_of([&] { ParticipantOptions::load_file(bad_period); }).find("announcement_period_s"),
      std::string::npos);
}

TEST(ParticipantOptionsFile, ShippedWifiProfileUsesUnicastPeers) {
  const auto wifi =
      ParticipantOptions::load_file(std::string(COVER_SOURCE_DIR) + "/config/dds.yaml", "wifi");
  EXPECT_EQ(wifi.interface_name, "wifi0");
  EXPECT_FALSE(wifi.peers.empty());
  // A vehicle's few processes per peer, not a whole fleet's: 72 x 32 peers per announcement
  // saturated the emulated 10 Mbit link (docs/benchmarks.md).
  EXPECT_LE(wifi.participants_per_peer, 8);
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
  Participant participant(cover::test::private_options(GetParam()));
  const auto topic = Topic<msg::UavStatus>::uncatalogued(
      cover::test::private_prefix("layer") + "/status", state_qos());
  std::atomic<int> callbacks{0};
  auto callback_reader =
      participant.make_reader(topic, [&](const msg::UavStatus&) { ++callbacks; });
  auto latest_reader = participant.make_reader(topic);
  auto writer = participant.make_writer(topic);
  ASSERT_TRUE(writer.wait_for_readers(2, 10s));
  msg::UavStatus status;
  status.task_id = "t1";
  status.stage = msg::Stage::STAGE_TRANSITION;
  ASSERT_TRUE(writer.write(status));
  ASSERT_TRUE(latest_reader.wait_for_sample(5s));
  ASSERT_TRUE(callback_reader.wait_for_sample(5s));
  EXPECT_EQ(latest_reader.latest()->sample, status);
  EXPECT_EQ(callbacks.load(), 1);
}

TEST_P(OnEachVendor, DeadlineMissesRiseWhenTheWriterStops) {
  Participant participant(cover::test::private_options(GetParam()));
  const QosProfile qos = topics::ugv_imu(0).qos();  // sensor: 50 ms deadline
  ASSERT_DOUBLE_EQ(qos.deadline_s, 0.05);
  const auto topic =
      Topic<msg::UgvImu>::uncatalogued(cover::test::private_prefix("deadline") + "/imu", qos);
  auto reader = participant.make_reader(topic);
  auto writer = participant.make_writer(topic);
  ASSERT_TRUE(writer.wait_for_readers(1, 10s));
  // 30 samples at 100 Hz: within the deadline, so at most a scheduling hiccup's misses.
  msg::UgvImu imu;
  for (std::uint32_t i = 0; i < 30; ++i) {
    imu.seq = i;
    writer.write(imu);
    std::this_thread::sleep_for(10ms);  // pacing a 100 Hz writer, not synchronisation
  }
  ASSERT_TRUE(cover::test::wait_until([&] { return reader.received_count() >= 20; }, 5s))
      << reader.received_count() << " of 30 samples arrived";
  const std::uint64_t while_writing = reader.deadline_misses();
  EXPECT_LE(while_writing, 5u) << "misses while samples came every 10 ms";
  // The writer stopped: a miss every 50 ms from now on.
  EXPECT_TRUE(
      cover::test::wait_until([&] { return reader.deadline_misses() >= while_writing + 3; }, 5s))
      << "deadline misses stayed at " << reader.deadline_misses();
}

TEST_P(OnEachVendor, WritersAndReadersMayOutliveTheParticipant) {
  auto participant = std::make_unique<Participant>(cover::test::private_options(GetParam()));
  const auto topic = Topic<msg::TaskStatus>::uncatalogued(
      cover::test::private_prefix("outlive") + "/task", state_qos());
  auto reader = participant->make_reader(topic);
  auto writer = participant->make_writer(topic);
  participant.reset();
  ASSERT_TRUE(writer.wait_for_readers(1, 10s));
  msg::TaskStatus status;
  status.task_id = "after";
  ASSERT_TRUE(writer.write(status));
  ASSERT_TRUE(reader.wait_for_sample(5s));
  EXPECT_EQ(reader.latest()->sample, status);
}

TEST_P(OnEachVendor, UncataloguedTopicMustNotUseACataloguedName) {
  Participant participant(cover::test::private_options(GetParam()));
  const auto impostor = Topic<msg::UavCommand>::uncatalogued("cover/uav/0/cmd", sensor_qos());
  const auto text = message_of([&] { participant.make_writer(impostor); });
  EXPECT_NE(text.find("cover/uav/<u>/cmd"), std::string::npos) << text;
  EXPECT_THROW(participant.make_reader(impostor), DdsError);
  EXPECT_NO_THROW(participant.make_writer(topics::uav_command(0)));
}

INSTANTIATE_TEST_SUITE_P(Vendors, OnEachVendor, testing::Values(Vendor::FastDds, Vendor::Cyclone),
                         [](const auto& info) { return std::string(vendor_name(info.param)); });

// Writer on the first vendor, late-joining reader on the second.
class LateJoiner : public testing::TestWithParam<std::pair<Vendor, Vendor>> {};

TEST_P(LateJoiner, StateDepthGivesItTheLastEightSamples) {
  const auto writer_options = cover::test::private_options(GetParam().first);
  const auto reader_options = cover::test::private_options(GetParam().second);
  const QosProfile qos = topics::uav_status(0).qos();  // state: transient-local, keep-last 8
  ASSERT_EQ(qos.history_depth, 8);
  ASSERT_EQ(qos.durability, Durability::TransientLocal);
  const auto topic =
      Topic<msg::UavStatus>::uncatalogued(cover::test::private_prefix("depth") + "/status", qos);
  Participant writer_side(writer_options);
  auto writer = writer_side.make_writer(topic);
  msg::UavStatus status;
  status.uav_id = 4;  // one instance: the depth is per instance
  for (std::uint32_t i = 1; i <= 12; ++i) {
    status.process_index = i;
    ASSERT_TRUE(writer.write(status));
  }

  Participant reader_side(reader_options);
  std::mutex mutex;
  std::vector<std::uint32_t> delivered;
  auto reader = reader_side.make_reader(topic, [&](const msg::UavStatus& sample) {
    std::lock_guard<std::mutex> lock(mutex);
    delivered.push_back(sample.process_index);
  });
  auto delivered_count = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return delivered.size();
  };
  ASSERT_TRUE(cover::test::wait_until([&] { return delivered_count() >= 8; }, 10s))
      << "the late joiner got " << delivered_count() << " of the last 8 samples";
  // A live sample after the history: reliable delivery is in order, so once it is in,
  // nothing more of the history can follow.
  status.process_index = 13;
  ASSERT_TRUE(writer.write(status));
  ASSERT_TRUE(cover::test::wait_until([&] { return delivered_count() >= 9; }, 10s));
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_EQ(delivered, (std::vector<std::uint32_t>{5, 6, 7, 8, 9, 10, 11, 12, 13}));
}

INSTANTIATE_TEST_SUITE_P(VendorPairs, LateJoiner,
                         testing::Values(std::pair{Vendor::FastDds, Vendor::FastDds},
                                         std::pair{Vendor::Cyclone, Vendor::Cyclone},
                                         std::pair{Vendor::FastDds, Vendor::Cyclone},
                                         std::pair{Vendor::Cyclone, Vendor::FastDds}),
                         [](const auto& info) {
                           return std::string(vendor_name(info.param.first)) + "_to_" +
                                  vendor_name(info.param.second);
                         });

// Keyed topics carry one instance per key: a task manager's task statuses are one per task.
// A vendor's default instance limit (Fast DDS: 10) must not silently drop the 11th task.
class ManyInstances : public testing::TestWithParam<std::pair<Vendor, Vendor>> {};

TEST_P(ManyInstances, EveryKeyIsDeliveredAndKeptForLateJoiners) {
  const auto topic = Topic<msg::TaskStatus>::uncatalogued(
      cover::test::private_prefix("instances") + "/task", topics::task_status().qos());
  Participant writer_side(cover::test::private_options(GetParam().first));
  Participant reader_side(cover::test::private_options(GetParam().second));
  std::mutex mutex;
  std::set<std::string> live;
  auto live_reader = reader_side.make_reader(topic, [&](const msg::TaskStatus& s) {
    std::lock_guard<std::mutex> lock(mutex);
    live.insert(s.task_id);
  });
  auto writer = writer_side.make_writer(topic);
  ASSERT_TRUE(writer.wait_for_readers(1, 10s));
  constexpr int kTasks = 60;
  for (int i = 0; i < kTasks; ++i) {
    msg::TaskStatus status;
    status.task_id = "task-" + std::to_string(i);
    ASSERT_TRUE(writer.write(status)) << "write of instance " << i << " refused";
  }
  auto count = [&](const std::set<std::string>& ids) {
    std::lock_guard<std::mutex> lock(mutex);
    return ids.size();
  };
  EXPECT_TRUE(cover::test::wait_until([&] { return count(live) == kTasks; }, 10s))
      << count(live) << " of " << kTasks << " instances arrived";
  std::set<std::string> late;
  auto late_reader = reader_side.make_reader(topic, [&](const msg::TaskStatus& s) {
    std::lock_guard<std::mutex> lock(mutex);
    late.insert(s.task_id);
  });
  EXPECT_TRUE(cover::test::wait_until([&] { return count(late) == kTasks; }, 10s))
      << "a late joiner got " << count(late) << " of " << kTasks << " instances";
}

INSTANTIATE_TEST_SUITE_P(VendorPairs, ManyInstances,
                         testing::Values(std::pair{Vendor::FastDds, Vendor::FastDds},
                                         std::pair{Vendor::Cyclone, Vendor::Cyclone},
                                         std::pair{Vendor::FastDds, Vendor::Cyclone},
                                         std::pair{Vendor::Cyclone, Vendor::FastDds}),
                         [](const auto& info) {
                           return std::string(vendor_name(info.param.first)) + "_to_" +
                                  vendor_name(info.param.second);
                         });

// The field configuration (no multicast, static unicast peers) on loopback, across vendors.
class UnicastPeers : public testing::TestWithParam<std::pair<Vendor, Vendor>> {};

TEST_P(UnicastPeers, DiscoverEachOtherWithoutMulticast) {
  ParticipantOptions writer_options = cover::test::private_options(GetParam().first);
  writer_options.peers = {"127.0.0.1"};
  ParticipantOptions reader_options = writer_options;
  reader_options.vendor = GetParam().second;
  Participant writer_side(writer_options);
  Participant reader_side(reader_options);
  const auto topic = Topic<msg::TaskStatus>::uncatalogued(
      cover::test::private_prefix("peers") + "/task", state_qos());
  auto reader = reader_side.make_reader(topic);
  auto writer = writer_side.make_writer(topic);
  ASSERT_TRUE(writer.wait_for_readers(1, 30s));
  msg::TaskStatus status;
  status.task_id = "peers";
  status.state = msg::TaskState::TASK_RUNNING;
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
