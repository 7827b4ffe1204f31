// The topic catalogue: typed descriptors, the runtime view built from them, and
// docs/topics.md, which must list exactly the catalogue.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cover/dds/dds_error.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace dds = cover::dds;
namespace msg = cover::msg;
namespace topics = cover::dds::topics;

namespace {

// --- What must not compile (checked here, at compile time) ---

template <typename T, typename TopicArg, typename = void>
struct CanMakeWriter : std::false_type {};
template <typename T, typename TopicArg>
struct CanMakeWriter<T, TopicArg,
                     std::void_t<decltype(std::declval<dds::Participant&>().make_writer<T>(
                         std::declval<const TopicArg&>()))>> : std::true_type {};

template <typename TopicArg, typename Callback, typename = void>
struct CanMakeReader : std::false_type {};
template <typename TopicArg, typename Callback>
struct CanMakeReader<TopicArg, Callback,
                     std::void_t<decltype(std::declval<dds::Participant&>().make_reader(
                         std::declval<const TopicArg&>(), std::declval<Callback>()))>>
    : std::true_type {};

template <typename T, typename = void>
struct CanMakeWriterByName : std::false_type {};
template <typename T>
struct CanMakeWriterByName<T, std::void_t<decltype(std::declval<dds::Participant&>().make_writer<T>(
                                  std::string(), dds::QosProfile()))>> : std::true_type {};

using CommandTopic = decltype(topics::uav_command(0));
static_assert(std::is_same_v<CommandTopic, dds::Topic<msg::UavCommand>>);
static_assert(CanMakeWriter<msg::UavCommand, CommandTopic>::value);
static_assert(!CanMakeWriter<msg::UavStatus, CommandTopic>::value,
              "a UavStatus writer on the command topic must not compile");
static_assert(CanMakeReader<CommandTopic, void (*)(const msg::UavCommand&)>::value);
static_assert(!CanMakeReader<CommandTopic, void (*)(const msg::UavStatus&)>::value,
              "a UavStatus callback on the command topic must not compile");
static_assert(!CanMakeWriterByName<msg::UavCommand>::value,
              "topics are not made from a free name and QoS");
static_assert(!std::is_constructible_v<dds::Topic<msg::UavStatus>, std::string, dds::QosProfile>,
              "only the catalogue and Topic::uncatalogued make topics");

// --- The accessors and the runtime view ---

template <typename T>
void expect_catalogued(const dds::Topic<T>& topic, const std::string& name,
                       std::set<std::string>& patterns) {
  SCOPED_TRACE(name);
  EXPECT_EQ(topic.name(), name);
  EXPECT_TRUE(topic.catalogued());
  const dds::TopicInfo* info = dds::find_topic(name);
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->type_name, T::kTypeName);
  EXPECT_EQ(topic.qos().name, info->qos_profile);
  patterns.insert(info->pattern);
  const auto looked_up = dds::catalogued_topic<T>(name);
  EXPECT_EQ(looked_up.name(), name);
  EXPECT_EQ(looked_up.qos().name, topic.qos().name);
}

TEST(TopicCatalog, EveryAccessorBindsItsRowAndEveryRowHasOne) {
  std::set<std::string> patterns;
  expect_catalogued(topics::ugv_imu(3), "cover/ugv/3/imu", patterns);
  expect_catalogued(topics::ugv_status(12), "cover/ugv/12/status", patterns);
  expect_catalogued(topics::relative_state(0, 2), "cover/uav/0/rel/2", patterns);
  expect_catalogued(topics::uav_command(1), "cover/uav/1/cmd", patterns);
  expect_catalogued(topics::uav_trace(1), "cover/uav/1/trace", patterns);
  expect_catalogued(topics::uav_status(7), "cover/uav/7/status", patterns);
  expect_catalogued(topics::uav_reference(2), "cover/uav/2/reference", patterns);
  expect_catalogued(topics::task_request(), "cover/task/request", patterns);
  expect_catalogued(topics::task_status(), "cover/task/status", patterns);
  expect_catalogued(topics::task_abort(), "cover/task/abort", patterns);
  expect_catalogued(topics::manager_request(), "cover/manager/request", patterns);
  expect_catalogued(topics::manager_reply(), "cover/manager/reply", patterns);
  expect_catalogued(topics::sim_clock(), "cover/sim/clock", patterns);
  expect_catalogued(topics::fc_state(3), "cover/uav/3/fc", patterns);
  expect_catalogued(topics::fc_request(), "cover/fc/request", patterns);
  expect_catalogued(topics::fc_reply(), "cover/fc/reply", patterns);
  expect_catalogued(topics::time_request(), "cover/time/request", patterns);
  expect_catalogued(topics::time_reply("cover-uav-agent-3"), "cover/time/reply/cover_uav_agent_3",
                    patterns);
  std::set<std::string> catalogued;
  for (const auto& entry : dds::topic_catalog()) catalogued.insert(entry.pattern);
  EXPECT_EQ(patterns, catalogued) << "a catalogue row without an accessor (or a test)";
  EXPECT_EQ(catalogued.size(), dds::topic_catalog().size()) << "a pattern listed twice";
}

TEST(TopicCatalog, QosComesFromTheRow) {
  EXPECT_EQ(topics::ugv_imu(0).qos().name, "sensor");
  EXPECT_EQ(topics::relative_state(0, 0).qos().name, "sensor");
  EXPECT_EQ(topics::uav_command(0).qos().name, "command");
  EXPECT_EQ(topics::uav_command(0).qos().reliability, dds::Reliability::Reliable);
  EXPECT_EQ(topics::task_request().qos().durability, dds::Durability::Volatile);  // no stale tasks
  EXPECT_EQ(topics::task_status().qos().durability, dds::Durability::TransientLocal);
}

TEST(TopicCatalog, NamesResolveOnlyWithDecimalIds) {
  EXPECT_EQ(dds::find_topic("cover/ugv/12/imu")->type_name, "cover::idl::UgvImu");
  EXPECT_EQ(dds::find_topic("cover/uav/0/rel/1")->type_name, "cover::idl::RelativeState");
  EXPECT_EQ(dds::find_topic("cover/ugv/x/imu"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/ugv/1/imu/extra"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/ugv//imu"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/ugv/<k>/imu"), nullptr);
}

TEST(TopicCatalog, EveryRowHasAKnownTypeAndProfileAndAValidName) {
  for (const auto& entry : dds::topic_catalog()) {
    SCOPED_TRACE(entry.pattern);
    EXPECT_TRUE(msg::with_type(entry.type_name, [](auto) {}));
    EXPECT_NO_THROW(dds::qos_profile(entry.qos_profile));
    EXPECT_FALSE(entry.rate.empty());
    EXPECT_NE(entry.flow.find(" -> "), std::string::npos);
    EXPECT_FALSE(entry.description.empty());
    // Cyclone accepts only [A-Za-z0-9_/] (placeholders become digits).
    for (const unsigned char c : entry.pattern) {
      EXPECT_TRUE(std::isalnum(c) || c == '_' || c == '/' || c == '<' || c == '>') << c;
    }
  }
}

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const dds::DdsError& e) {
    return e.what();
  }
  return "";
}

TEST(TopicCatalog, RuntimeLookupRefusesAWrongTypeOrAnUnknownName) {
  const auto wrong = message_of([] { dds::catalogued_topic<msg::UavStatus>("cover/uav/0/cmd"); });
  EXPECT_NE(wrong.find("cover::idl::UavCommand"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("cover::idl::UavStatus"), std::string::npos) << wrong;
  const auto unknown = message_of([] { dds::catalogued_topic<msg::UavStatus>("cover/uav/0/x"); });
  EXPECT_NE(unknown.find("not in the catalogue"), std::string::npos) << unknown;
}

// A clock reply topic per asker: its process name, as Cyclone takes it ([A-Za-z0-9_/]).
TEST(TopicCatalog, ReplyTopicsAreNamedByTheirAsker) {
  EXPECT_EQ(topics::time_reply("cover-task-manager").name(), "cover/time/reply/cover_task_manager");
  EXPECT_EQ(topics::time_reply("time-sync.test_2").name(), "cover/time/reply/time_sync_test_2");
  EXPECT_EQ(dds::find_topic("cover/time/reply/cover_sim")->type_name, "cover::idl::TimeSyncReply");
  EXPECT_EQ(dds::find_topic("cover/time/reply"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/time/reply/"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/time/reply/cover-sim"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/time/reply/a/b"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/time/reply/*"), nullptr);
  EXPECT_EQ(dds::find_topic("cover/time/reply/" + std::string(65, 'a')), nullptr);
  const std::vector<std::string> bad_names{"", "host/cover-sim", "a b", "cover*",
                                           std::string(65, 'a')};
  for (const std::string& bad : bad_names) {
    EXPECT_FALSE(dds::valid_process_name(bad)) << bad;
    EXPECT_NE(message_of([&] { topics::time_reply(bad); }).find("cannot name a clock reply topic"),
              std::string::npos)
        << bad;
  }
  EXPECT_EQ(topics::clock_askers(2, 1),
            (std::vector<std::string>{"cover-task-manager", "cover-uav-agent-0",
                                      "cover-uav-agent-1", "cover-ugv-agent-0"}));
}

// --- docs/topics.md ---

struct DocRow {
  std::string type, rate, qos, flow;
  bool operator==(const DocRow& other) const {
    return type == other.type && rate == other.rate && qos == other.qos && flow == other.flow;
  }
};

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(' ');
  const auto last = text.find_last_not_of(' ');
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

std::string unquote(const std::string& cell) {
  return cell.size() >= 2 && cell.front() == '`' && cell.back() == '`'
             ? cell.substr(1, cell.size() - 2)
             : cell;
}

// The rows of the table headed "| topic | type | rate | QoS profile | publisher -> ...",
// by topic pattern.
std::map<std::string, DocRow> documented_topics() {
  std::ifstream docs(std::string(COVER_SOURCE_DIR) + "/docs/topics.md");
  EXPECT_TRUE(docs) << "docs/topics.md is missing";
  std::map<std::string, DocRow> rows;
  std::string line;
  bool in_table = false;
  while (std::getline(docs, line)) {
    if (line.rfind("| topic | type | rate | QoS profile | publisher -> subscribers |", 0) == 0) {
      in_table = true;
      std::getline(docs, line);  // | --- | ...
      continue;
    }
    if (!in_table) continue;
    if (line.rfind("|", 0) != 0) break;
    std::vector<std::string> cells;
    for (std::size_t start = 1, bar; (bar = line.find(" |", start)) != std::string::npos;
         start = bar + 2) {
      cells.push_back(trim(line.substr(start, bar - start)));
    }
    EXPECT_EQ(cells.size(), 5u) << line;
    if (cells.size() != 5) continue;
    EXPECT_EQ(rows.count(unquote(cells[0])), 0u) << "listed twice: " << line;
    rows[unquote(cells[0])] = DocRow{unquote(cells[1]), cells[2], cells[3], cells[4]};
  }
  return rows;
}

TEST(TopicDocs, TableEqualsTheCatalogueBothWays) {
  const auto documented = documented_topics();
  ASSERT_FALSE(documented.empty()) << "no topic table found in docs/topics.md";
  std::map<std::string, DocRow> catalogued;
  for (const auto& entry : dds::topic_catalog()) {
    const std::string short_type = entry.type_name.substr(entry.type_name.rfind(':') + 1);
    catalogued[entry.pattern] = DocRow{short_type, entry.rate, entry.qos_profile, entry.flow};
  }
  for (const auto& [pattern, row] : catalogued) {
    const auto found = documented.find(pattern);
    if (found == documented.end()) {
      ADD_FAILURE() << pattern << " is in the catalogue, not in docs/topics.md";
    } else {
      EXPECT_TRUE(found->second == row)
          << pattern << ": docs say | " << found->second.type << " | " << found->second.rate
          << " | " << found->second.qos << " | " << found->second.flow << " |, the code | "
          << row.type << " | " << row.rate << " | " << row.qos << " | " << row.flow
          << " | (regenerate with `cover topics --markdown`)";
    }
  }
  for (const auto& [pattern, row] : documented) {
    EXPECT_EQ(catalogued.count(pattern), 1u)
        << pattern << " is in docs/topics.md, not in the catalogue";
  }
}

}  // namespace
