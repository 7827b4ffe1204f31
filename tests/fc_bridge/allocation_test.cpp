// The latency path must not touch the heap: count every global allocation while the
// bridge turns agent commands into setpoints in flight.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "cover/fc_bridge/bridge.hpp"
#include "fake_autopilot.hpp"

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

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;

TEST(FcBridgeAllocation, CommandsInFlightDoNotAllocate) {
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
    const long before = g_allocations.load();
    frames += step(i);
    allocations += g_allocations.load() - before;
  }
  EXPECT_EQ(frames, 1000U);
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(bridge.notices().empty());
}

}  // namespace
}  // namespace cover::fc_bridge
