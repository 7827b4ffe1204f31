// The control loop must not touch the heap: count every global allocation while SAMPC runs.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <iterator>
#include <new>

#include "cover/sampc/sampc.hpp"

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

namespace cover::sampc {
namespace {

TEST(SampcAllocation, TheControlLoopDoesNotAllocate) {
  SampcParams params;
  Sampc mpc(params);
  SampcInput in;
  in.stage = model::Stage::Transition;
  in.uav_state = model::uav_state_at_rest(Eigen::Vector3d(2.0, -1.0, 1.2));
  in.ugv.angular_velocity_rad_s = Eigen::Vector3d(0.0, 0.0, 0.4);
  in.ugv.speed_m_s = 0.8;  // the intercept method's prediction is in use
  in.ugv.speed_source = model::SpeedSource::WheelOdometry;
  in.ugv.forward_acceleration_m_s2 = 0.2;
  in.reference = HorizonReference::hold(Eigen::Vector3d(0.0, 0.0, 1.5));
  // An approach at the speed limit: intercept solves its fastest straight flight.
  for (Eigen::Vector3d& v : in.reference.velocity_m_s)
    v = Eigen::Vector3d(-in.speed_limit_m_s, 0, 0);
  mpc.solve(in);  // cold start outside the count

  const long before = g_allocations.load();
  for (int i = 0; i < 50; ++i) {
    in.stage = static_cast<model::Stage>(i / 20);
    in.uav_state(0) -= 0.01;
    // A task's process may switch the method at run time.
    mpc.set_mode(kModes[(i / 5) % std::size(kModes)]);
    if (i == 25) mpc.reset_frame();  // the switch's smoothing and intercept's lead ramp
    mpc.prepare(in);
    const SampcOutput out = mpc.feedback(in);
    ASSERT_FALSE(is_error(out.status));
  }
  mpc.reset();
  mpc.solve(in);  // cold start after a reset, too
  EXPECT_EQ(g_allocations.load() - before, 0);
}

}  // namespace
}  // namespace cover::sampc
