// The latency path must not touch the heap: count every allocation (malloc:
// cover/test/malloc_counter.hpp; its own executable) while the bridge turns agent commands
// into setpoints in flight.
#include <gtest/gtest.h>

#include "cover/fc_bridge/bridge.hpp"
#include "cover/test/malloc_counter.hpp"
#include "fake_autopilot.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;

TEST(FcBridgeAllocation, CommandsInFlightDoNotAllocate) {
  if (!cover::test::malloc_counted()) GTEST_SKIP() << "malloc belongs to the sanitizer";
  BridgeConfig config;
  Bridge bridge(config);
  test::FakeAutopilot autopilot(5, mav::mav_autopilot::kPx4);
  double t = 10.0;
  const auto offboard = mav::px4_mode::custom_mode(mav::px4_mode::kMainOffboard);
  bridge.on_frame(autopilot.heartbeat(true, offboard), t);
  bridge.on_frame(autopilot.landed(mav::mav_landed_state::kInAir), t);
  AgentCommand c;
  c.thrust_m_s2 = 9.81;
  c.armed = true;
  auto step = [&](int i) {
    t += 0.01;
    c.stamp_ns = static_cast<std::int64_t>(t * 1e9);
    c.seq = static_cast<std::uint32_t>(i);
    c.pitch_rate_rad_s = 0.01 * (i % 7);
    return bridge.on_agent_command(c, t).size();
  };
  for (int i = 0; i < 200; ++i) step(i);  // warm up: the first notices, the stream
  bridge.notices().clear();
  long allocations = 0;
  std::size_t frames = 0;
  for (int i = 200; i < 1200; ++i) {
    if (i % 100 == 0) bridge.on_frame(autopilot.heartbeat(true, offboard), t);  // uncounted
    const long before = cover::test::counted_allocations();
    cover::test::count_this_thread(true);
    frames += step(i);
    cover::test::count_this_thread(false);
    allocations += cover::test::counted_allocations() - before;
  }
  EXPECT_EQ(frames, 1000U);
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(bridge.notices().empty());
}

}  // namespace
}  // namespace cover::fc_bridge
