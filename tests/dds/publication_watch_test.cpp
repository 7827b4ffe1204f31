// Participant::watch_publications on both vendors and across them: the writers of other
// participants, those that existed before the watch and those made after it, with their
// topic and type names; never this participant's own writers; nothing after stop().
#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "dds_test_support.hpp"

namespace {

using namespace cover::dds;
using namespace std::chrono_literals;
namespace msg = cover::msg;
using cover::test::private_options;
using cover::test::wait_until;

// What a watch reported, safe to read while the vendor thread reports more.
class Heard {
 public:
  PublicationHandler handler() {
    return [this](const DiscoveredPublication& p) {
      std::lock_guard<std::mutex> lock(mutex_);
      heard_.push_back(p);
    };
  }
  // The type name reported for `topic`, or "" when it was not reported.
  std::string type_of(const std::string& topic) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& p : heard_) {
      if (p.topic_name == topic) return p.type_name;
    }
    return "";
  }
  bool heard(const std::string& topic) const { return !type_of(topic).empty(); }
  std::size_t count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return heard_.size();
  }

 private:
  mutable std::mutex mutex_;
  std::vector<DiscoveredPublication> heard_;
};

class PublicationWatchTest : public ::testing::TestWithParam<std::pair<Vendor, Vendor>> {
 protected:
  Vendor watcher_vendor() const { return GetParam().first; }
  Vendor writer_vendor() const { return GetParam().second; }
};

TEST_P(PublicationWatchTest, ReportsOtherParticipantsWritersMadeBeforeAndAfterTheWatch) {
  Participant watcher(private_options(watcher_vendor()));
  Participant publisher(private_options(writer_vendor()));
  auto before = publisher.make_writer(topics::ugv_imu(3));
  // The watcher knows the first writer before the watch starts: its own reader matched it.
  auto probe = watcher.make_reader(topics::ugv_imu(3));
  ASSERT_TRUE(probe.wait_for_writers(1, cover::test::scaled(20s)));
  auto own = watcher.make_writer(topics::uav_status(2));

  Heard heard;
  PublicationWatch watch = watcher.watch_publications(heard.handler());
  auto after = publisher.make_writer(topics::relative_state(1, 2));

  ASSERT_TRUE(wait_until([&] { return heard.heard("cover/uav/1/rel/2"); }, 20s))
      << "the writer made after the watch was not reported";
  EXPECT_EQ(heard.type_of("cover/ugv/3/imu"), msg::UgvImu::kTypeName)
      << "the writer known before the watch was not reported";
  EXPECT_EQ(heard.type_of("cover/uav/1/rel/2"), msg::RelativeState::kTypeName);
  EXPECT_FALSE(heard.heard("cover/uav/2/status")) << "the watcher's own writer was reported";
}

TEST_P(PublicationWatchTest, ReportsNothingAfterStop) {
  Participant watcher(private_options(watcher_vendor()));
  Participant publisher(private_options(writer_vendor()));
  Heard heard;
  PublicationWatch watch = watcher.watch_publications(heard.handler());
  auto first = publisher.make_writer(topics::uav_trace(3));
  ASSERT_TRUE(wait_until([&] { return heard.heard("cover/uav/3/trace"); }, 20s));
  watch.stop();
  const std::size_t reported = heard.count();

  // Discovery certainly learnt the second writer once a reader of the watcher matched it.
  auto second = publisher.make_writer(topics::uav_reference(3));
  auto probe = watcher.make_reader(topics::uav_reference(3));
  ASSERT_TRUE(probe.wait_for_writers(1, cover::test::scaled(20s)));
  EXPECT_EQ(heard.count(), reported);
  EXPECT_FALSE(heard.heard("cover/uav/3/reference"));
}

std::string pair_name(const ::testing::TestParamInfo<std::pair<Vendor, Vendor>>& info) {
  return std::string(vendor_name(info.param.first)) + "_watches_" + vendor_name(info.param.second);
}

INSTANTIATE_TEST_SUITE_P(EveryVendorPair, PublicationWatchTest,
                         ::testing::Values(std::pair{Vendor::FastDds, Vendor::FastDds},
                                           std::pair{Vendor::Cyclone, Vendor::Cyclone},
                                           std::pair{Vendor::FastDds, Vendor::Cyclone},
                                           std::pair{Vendor::Cyclone, Vendor::FastDds}),
                         pair_name);

}  // namespace
