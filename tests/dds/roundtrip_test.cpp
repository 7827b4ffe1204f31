// Every catalogue type, field by field, between two real processes on every vendor pair.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/process/child_process.hpp"
#include "dds_test_support.hpp"
#include "sample_fill.hpp"

using cover::dds::Vendor;
using namespace std::chrono_literals;

namespace {

struct VendorPair {
  Vendor local;
  Vendor remote;
};

std::string pair_name(const testing::TestParamInfo<VendorPair>& info) {
  return std::string(cover::dds::vendor_name(info.param.local)) + "_to_" +
         cover::dds::vendor_name(info.param.remote);
}

template <typename T>
std::string short_name() {
  const std::string full = T::kTypeName;
  return full.substr(full.rfind(':') + 1);
}

class RoundTrip : public testing::TestWithParam<VendorPair> {};

// Writes one filled sample of T to the peer and expects the identical sample back.
template <typename T>
void expect_round_trip(cover::dds::Participant& participant, const std::string& prefix,
                       std::uint64_t seed) {
  SCOPED_TRACE(T::kTypeName);
  const std::string base = prefix + "/" + short_name<T>();
  using Topic = cover::dds::Topic<T>;
  auto reader =
      participant.make_reader(Topic::uncatalogued(base + "/out", cover::dds::state_qos()));
  auto writer = participant.make_writer(Topic::uncatalogued(base + "/in", cover::dds::state_qos()));
  ASSERT_TRUE(writer.wait_for_readers(1, 15s)) << "peer's reader never matched";
  ASSERT_TRUE(reader.wait_for_writers(1, 15s)) << "peer's writer never matched";

  T sent{};
  cover::test::SampleFiller(seed).fill(sent);
  ASSERT_TRUE(writer.write(sent));
  ASSERT_TRUE(reader.wait_for_sample(10s)) << "no echo received";
  const auto received = reader.latest();
  ASSERT_TRUE(received.has_value());
  EXPECT_EQ(cover::test::first_difference(sent, received->sample), "");
  EXPECT_TRUE(sent == received->sample);
}

TEST_P(RoundTrip, EveryTypeSurvivesFieldByField) {
  const std::string prefix = cover::test::private_prefix("roundtrip");
  const auto options = cover::test::private_options(GetParam().local);

  cover::process::ChildProcess peer(
      {COVER_DDS_PEER, "--dds", cover::dds::vendor_name(GetParam().remote), "--domain",
       std::to_string(options.domain_id), "--prefix", prefix},
      {}, /*capture_stdout=*/true);
  const auto ready = peer.read_line(20s);
  ASSERT_TRUE(ready.has_value()) << "peer did not start";
  ASSERT_EQ(*ready, "ready");

  cover::dds::Participant participant(options);
  std::uint64_t seed = 1000;
  cover::msg::for_each_type([&](auto tag) {
    using T = typename decltype(tag)::type;
    expect_round_trip<T>(participant, prefix, seed += 100);
  });
  EXPECT_EQ(peer.terminate(), 0) << "peer did not exit cleanly on SIGTERM";
}

INSTANTIATE_TEST_SUITE_P(VendorPairs, RoundTrip,
                         testing::Values(VendorPair{Vendor::FastDds, Vendor::FastDds},
                                         VendorPair{Vendor::Cyclone, Vendor::Cyclone},
                                         VendorPair{Vendor::FastDds, Vendor::Cyclone},
                                         VendorPair{Vendor::Cyclone, Vendor::FastDds}),
                         pair_name);

}  // namespace
