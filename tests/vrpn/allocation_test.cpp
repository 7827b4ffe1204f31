// The VRPN session parses without allocating once the remote names are known, lost
// samples, pings (outgoing capacity reserved) and refused messages included: every global
// operator new is counted while it parses. Its own binary: it replaces operator new.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <limits>
#include <new>

#include "cover/vrpn/client_session.hpp"
#include "spec_bytes.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace {

using namespace cover::test::vrpn_spec;

TEST(VrpnAllocation, TheSessionDoesNotAllocatePerMessage) {
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
  const long before = g_allocations.load();
  for (std::size_t at = 0; at < stream.size(); at += 61) {
    ASSERT_TRUE(
        session.feed(stream.data() + at, std::min<std::size_t>(61, stream.size() - at), on));
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(reports, 1000u);
  EXPECT_EQ(session.stats().unknown_sender, 500u);
}

}  // namespace
