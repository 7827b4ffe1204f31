// DDS-Security settings and the access rules the permissions are made from (no
// certificates here: tests/integration/security_test.cpp runs real secure processes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <set>
#include <string>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/access_rules.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/dds/security_check.hpp"
#include "cover/dds/topics.hpp"
#include "cover/test/scratch_dir.hpp"
#include "dds_test_support.hpp"

namespace cover::dds {
namespace {

using cover::test::message_of;
using cover::test::write_temp_yaml;

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

TEST(SecurityOptions, OffByDefaultAndInTheShippedConfig) {
  EXPECT_FALSE(ParticipantOptions{}.security.enabled);
  const auto shipped =
      ParticipantOptions::load_file(std::string(COVER_SOURCE_DIR) + "/config/dds.yaml");
  EXPECT_FALSE(shipped.security.enabled);
  const auto field =
      ParticipantOptions::load_file(std::string(COVER_SOURCE_DIR) + "/config/dds.yaml", "field");
  EXPECT_TRUE(field.security.enabled);
  EXPECT_FALSE(field.security.directory.empty());
  EXPECT_EQ(field.interface_name, "wlan0");
}

TEST(SecurityOptions, LoadRejectsUnknownKeysAndNamesMissingOnes) {
  const auto typo = write_temp_yaml("sec_typo.yaml", "dds:\n  security:\n    directroy: /x\n");
  EXPECT_NE(message_of([&] { ParticipantOptions::load_file(typo); }).find("directroy"),
            std::string::npos);
  // The identity may come from the command line: the file alone need not name it, but a
  // participant without one is refused.
  const auto no_identity =
      write_temp_yaml("sec_noid.yaml", "dds:\n  security:\n    enabled: true\n    directory: /x\n");
  const ParticipantOptions without = ParticipantOptions::load_file(no_identity);
  EXPECT_NE(message_of([&] { check_participant_security(without); }).find("no identity"),
            std::string::npos);
  const auto no_dir = write_temp_yaml("sec_nodir.yaml",
                                      "dds:\n  security:\n    enabled: true\n    identity: sim\n");
  const ParticipantOptions no_directory = ParticipantOptions::load_file(no_dir);
  EXPECT_NE(
      message_of([&] { check_participant_security(no_directory); }).find("no fleet directory"),
      std::string::npos);
  const auto in_profile = write_temp_yaml(
      "sec_profile.yaml",
      "dds:\n  profiles:\n    secure:\n      security: {enabled: true, directory: /f, "
      "identity: sim}\n    other:\n      security: {enabeld: true}\n");
  EXPECT_NE(message_of([&] { ParticipantOptions::load_file(in_profile); }).find("enabeld"),
            std::string::npos);
}

TEST(SecurityOptions, ExpiryWarningWindowIsReadAndChecked) {
  EXPECT_EQ(SecurityOptions{}.expiry_warning_days, 14);
  const auto shipped =
      ParticipantOptions::load_file(std::string(COVER_SOURCE_DIR) + "/config/dds.yaml", "field");
  EXPECT_EQ(shipped.security.expiry_warning_days, 14);
  const auto thirty = ParticipantOptions::from_yaml(
      config::parse_yaml("dds:\n  security:\n    expiry_warning_days: 30\n", "w.yaml"), "w.yaml");
  EXPECT_EQ(thirty.security.expiry_warning_days, 30);
  for (const char* bad : {"-1", "3651", "1.5", ".nan"}) {
    const std::string text = std::string("dds:\n  security:\n    expiry_warning_days: ") + bad;
    EXPECT_NE(message_of([&] {
                ParticipantOptions::from_yaml(config::parse_yaml(text, "w.yaml"), "w.yaml");
              }).find("expiry_warning_days"),
              std::string::npos)
        << bad;
  }
}

TEST(SecurityExpiry, WindowAndTimeLeftText) {
  EXPECT_TRUE(expires_within(13 * 86400, 14));
  EXPECT_FALSE(expires_within(14 * 86400, 14));
  EXPECT_TRUE(expires_within(-5, 0));  // expired: always
  EXPECT_FALSE(expires_within(1, 0));  // a window of 0 days warns of nothing still valid
  EXPECT_EQ(time_left_text(86400 + 3 * 3600 + 4 * 60 + 59), "1 d 3 h 4 min");
  EXPECT_EQ(time_left_text(0), "expired");
  IdentityReport report;
  report.name = "uav-agent-0";
  report.not_after_utc = "2026-12-02T17:00:00Z";
  report.expires_first = "certificate";
  report.seconds_to_expiry = 86400;
  const std::string warning = expiry_warning(report, 14);
  EXPECT_NE(warning.find("uav-agent-0 expires on 2026-12-02T17:00:00Z (its certificate), in 1 d"),
            std::string::npos)
      << warning;
  EXPECT_EQ(expiry_warning(report, 1), "");
}

TEST(SecurityOptions, EnvironmentTurnsItOn) {
  setenv("COVER_DDS_SECURITY", "/fleet", 1);
  setenv("COVER_DDS_IDENTITY", "uav-agent-3", 1);
  const ParticipantOptions options = apply_environment(ParticipantOptions{});
  unsetenv("COVER_DDS_SECURITY");
  unsetenv("COVER_DDS_IDENTITY");
  EXPECT_TRUE(options.security.enabled);
  EXPECT_EQ(options.security.directory, "/fleet");
  EXPECT_EQ(options.security.identity, "uav-agent-3");
  const SecurityFiles files = SecurityFiles::of("/fleet", "uav-agent-3");
  EXPECT_EQ(files.certificate, "/fleet/identities/uav-agent-3/cert.pem");
  EXPECT_EQ(files.governance, "/fleet/governance.p7s");
}

// A secure participant whose files are missing is never made plain: creation throws.
TEST(SecurityOptions, MissingFleetIsAnErrorNotAPlainParticipant) {
  for (const Vendor vendor : {Vendor::FastDds, Vendor::Cyclone}) {
    ParticipantOptions options;
    options.vendor = vendor;
    options.domain_id = 180;
    options.security = {true, cover::test::scratch_path("no_such_fleet"), "sim"};
    const std::string message = message_of([&] { Participant participant(options); });
    EXPECT_NE(message.find("no_such_fleet/fleet.yaml"), std::string::npos) << message;
    options.domain_id = 231;
    EXPECT_NE(message_of([&] { check_participant_security(options); }).find("0..230"),
              std::string::npos);
  }
}

TEST(Identities, NamesRoundTripAndOthersAreRefused) {
  for (const Identity identity : fleet_identities(Fleet{3, 2, 2})) {
    const auto parsed = parse_identity(identity_name(identity));
    ASSERT_TRUE(parsed) << identity_name(identity);
    EXPECT_EQ(*parsed, identity);
  }
  EXPECT_EQ(identity_name({Role::UavAgent, 4}), "uav-agent-4");
  for (const char* bad : {"", "uav-agent-", "uav-agent-x", "uav-agent-01", "sim0", "root",
                          "ground-station--1", "uav-agent-1234567"}) {
    EXPECT_FALSE(parse_identity(bad)) << bad;
  }
  // sim, task-manager, mocap-relay, 2 UGV agents, a UAV agent, its bridge, a ground station.
  EXPECT_EQ(fleet_identities(Fleet{2, 1, 1}).size(), 8u);
}

// Least privilege, from the catalogue: every catalogued topic of the fleet has exactly
// the writers the issue names, and somebody reads it.
TEST(AccessRules, LeastPrivilegeOverTheWholeCatalogue) {
  const Fleet fleet{2, 2, 1};
  std::set<std::string> published, subscribed;
  const auto writers = [&](const std::string& topic) {
    std::set<std::string> who;
    for (const auto& identity : fleet_identities(fleet)) {
      if (contains(topic_access(identity, fleet).publish, topic))
        who.insert(identity_name(identity));
    }
    return who;
  };
  for (const auto& identity : fleet_identities(fleet)) {
    const TopicAccess access = topic_access(identity, fleet);
    published.insert(access.publish.begin(), access.publish.end());
    subscribed.insert(access.subscribe.begin(), access.subscribe.end());
    // A '*' stands for every process's reply topic (a DDS-Security fnmatch pattern).
    for (auto topic : access.publish) {
      if (const auto star = topic.find('*'); star != std::string::npos) topic.replace(star, 1, "x");
      EXPECT_TRUE(find_topic(topic)) << topic;
    }
  }
  using Names = std::set<std::string>;
  EXPECT_EQ(writers(topics::uav_command(1).name()), Names{"uav-agent-1"});
  EXPECT_EQ(writers(topics::task_request().name()), Names{"task-manager"});
  EXPECT_EQ(writers(topics::manager_request().name()), Names{"ground-station-0"});
  EXPECT_EQ(writers(topics::relative_state(1, 0).name()), (Names{"mocap-relay", "sim"}));
  EXPECT_EQ(writers(topics::ugv_imu(1).name()), Names{"ugv-agent-1"});
  // Every catalogue pattern is published and subscribed by someone in the fleet.
  for (const auto& info : topic_catalog()) {
    const auto has = [&](const std::set<std::string>& names) {
      return std::any_of(names.begin(), names.end(), [&](std::string n) {
        if (const auto star = n.find('*'); star != std::string::npos) n.replace(star, 1, "x");
        return find_topic(n) == &info;
      });
    };
    EXPECT_TRUE(has(published)) << info.pattern;
    EXPECT_TRUE(has(subscribed)) << info.pattern;
  }
  // A UAV agent reads only its own relative states.
  const TopicAccess uav0 = topic_access({Role::UavAgent, 0}, fleet);
  EXPECT_TRUE(contains(uav0.subscribe, topics::relative_state(0, 1).name()));
  EXPECT_FALSE(contains(uav0.subscribe, topics::relative_state(1, 1).name()));
  // Only its own bridge flies a UAV's commands and reports its autopilot; only ground
  // stations may arm, switch or land an autopilot.
  const TopicAccess bridge0 = topic_access({Role::FcBridge, 0}, fleet);
  EXPECT_TRUE(contains(bridge0.subscribe, topics::uav_command(0).name()));
  EXPECT_FALSE(contains(bridge0.subscribe, topics::uav_command(1).name()));
  EXPECT_TRUE(contains(bridge0.publish, topics::fc_state(0).name()));
  EXPECT_FALSE(contains(bridge0.publish, topics::fc_state(1).name()));
  EXPECT_FALSE(contains(bridge0.publish, topics::uav_command(0).name()));
  EXPECT_TRUE(contains(bridge0.subscribe, topics::fc_request().name()));
  EXPECT_FALSE(contains(uav0.publish, topics::fc_request().name()));
  EXPECT_TRUE(contains(uav0.subscribe, topics::fc_state(0).name()));
  const TopicAccess station = topic_access({Role::GroundStation, 0}, fleet);
  EXPECT_TRUE(contains(station.publish, topics::fc_request().name()));
  EXPECT_EQ(identity_name({Role::FcBridge, 1}), "fc-bridge-1");
  EXPECT_EQ(parse_identity("fc-bridge-1")->role, Role::FcBridge);
  // The motion-capture relay publishes every relative state; it reads only clock requests
  // (the UAV agents measure its clock: it stamps their relative states).
  const TopicAccess relay = topic_access({Role::MocapRelay, 0}, fleet);
  EXPECT_TRUE(contains(relay.publish, topics::relative_state(1, 0).name()));
  EXPECT_FALSE(contains(relay.publish, topics::uav_command(0).name()));
  EXPECT_EQ(relay.subscribe.size(), 1u);
  EXPECT_EQ(identity_name({Role::MocapRelay, 0}), "mocap-relay");
  // Clock replies: every answerer may write any asker's topic; an asker reads its own only.
  const std::string any_reply = "cover/time/reply/*";
  EXPECT_EQ(writers(any_reply),
            (Names{"fc-bridge-0", "fc-bridge-1", "mocap-relay", "sim", "uav-agent-0", "uav-agent-1",
                   "ugv-agent-0", "ugv-agent-1"}));
  EXPECT_TRUE(contains(relay.publish, any_reply));
  EXPECT_TRUE(contains(uav0.subscribe, topics::time_reply("cover-uav-agent-0").name()));
  EXPECT_FALSE(contains(uav0.subscribe, topics::time_reply("cover-uav-agent-1").name()));
  EXPECT_FALSE(contains(uav0.subscribe, any_reply));
  EXPECT_TRUE(contains(topic_access({Role::TaskManager, 0}, fleet).subscribe,
                       topics::time_reply("cover-task-manager").name()));
  EXPECT_TRUE(contains(topic_access({Role::UgvAgent, 1}, fleet).subscribe,
                       topics::time_reply("cover-ugv-agent-1").name()));
  EXPECT_FALSE(contains(bridge0.subscribe, topics::time_reply("cover-fc-bridge-0").name()));
  EXPECT_TRUE(contains(station.subscribe, any_reply));
  EXPECT_FALSE(contains(station.publish, any_reply));
  EXPECT_EQ(parse_identity("mocap-relay")->role, Role::MocapRelay);
}

}  // namespace
}  // namespace cover::dds
