// The VRPN session parses without allocating once the remote names are known, lost
// samples, pings (outgoing capacity reserved) and refused messages included: every
// allocation is counted while it parses (cover/test/malloc_counter.hpp; its own binary).
#include <gtest/gtest.h>

#include <limits>

#include "cover/test/malloc_counter.hpp"
#include "cover/vrpn/client_session.hpp"
#include "spec_bytes.hpp"

namespace {

using namespace cover::test::vrpn_spec;

TEST(VrpnAllocation, TheSessionDoesNotAllocatePerMessage) {
  if (!cover::test::malloc_counted()) GTEST_SKIP() << "malloc belongs to the sanitizer";
  cover::vrpn::SessionOptions options;
  options.bodies = {"UAV_A", "Truck_2"};
  cover::vrpn::ClientSession session(options);
  session.start();
  const Bytes warm_up = cat({cookie(), sender_uav_a_id0(), type_pos_quat_id5()});
  Bytes nan_pose = pos_quat_sender0_type5();
  for (int i = 24 + 8; i < 24 + 32; ++i) nan_pose[i] = 0xff;  // NaN position
  Bytes unknown = pos_quat_sender0_type5();
  unknown[15] = 9;  // sender 9: never described
  Bytes stream;
  for (int i = 0; i < 500; ++i) stream = cat({stream, pos_quat_sender0_type5(), nan_pose, unknown});
  std::uint64_t reports = 0;
  const cover::vrpn::ReportHandler on = [&](const cover::vrpn::TrackerReport&) { ++reports; };
  ASSERT_TRUE(session.feed(warm_up.data(), warm_up.size(), on));
  session.consume_outgoing(session.outgoing_bytes());
  const long before = cover::test::counted_allocations();
  bool fed = true;
  cover::test::count_this_thread(true);
  for (std::size_t at = 0; at < stream.size() && fed; at += 61) {
    fed = session.feed(stream.data() + at, std::min<std::size_t>(61, stream.size() - at), on);
  }
  cover::test::count_this_thread(false);
  ASSERT_TRUE(fed);
  EXPECT_EQ(cover::test::counted_allocations() - before, 0);
  EXPECT_EQ(reports, 1000u);
  EXPECT_EQ(session.stats().unknown_sender, 500u);
}

}  // namespace
