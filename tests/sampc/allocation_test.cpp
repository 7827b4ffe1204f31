// The control loop must not touch the heap: count every allocation (malloc, so Eigen's too:
// cover/test/malloc_counter.hpp; its own executable) while SAMPC runs.
#include <gtest/gtest.h>

#include <iterator>

#include "cover/sampc/sampc.hpp"
#include "cover/test/malloc_counter.hpp"

namespace cover::sampc {
namespace {

TEST(SampcAllocation, TheControlLoopDoesNotAllocate) {
  if (!cover::test::malloc_counted())
    GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
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

  const long before = cover::test::counted_allocations();
  int errors = 0;
  cover::test::count_this_thread(true);
  for (int i = 0; i < 50; ++i) {
    in.stage = static_cast<model::Stage>(i / 20);
    in.uav_state(0) -= 0.01;
    // A task's process may switch the method at run time.
    mpc.set_mode(kModes[(i / 5) % std::size(kModes)]);
    if (i == 25) mpc.reset_frame();  // the switch's smoothing and intercept's lead ramp
    mpc.prepare(in);
    const SampcOutput out = mpc.feedback(in);
    errors += is_error(out.status) ? 1 : 0;
  }
  // The flying loop's real-time iteration: prepare on the state predicted from the last
  // command, then the feedback on the measurement (MissionController::prepare_next_step),
  // rehearsed just before it as the realtime agent does.
  int prepared_ahead = 0;
  for (int i = 0; i < 20; ++i) {
    SampcInput predicted = in;
    predicted.uav_state = mpc.predicted_state(params.control_period_s);
    mpc.prepare(predicted);
    prepared_ahead += mpc.prepared() ? 1 : 0;
    mpc.rehearse_feedback();
    in.uav_state(0) -= 0.01;
    const SampcOutput out = mpc.feedback(in);
    errors += is_error(out.status) ? 1 : 0;
  }
  mpc.reset();
  mpc.solve(in);  // cold start after a reset, too
  cover::test::count_this_thread(false);
  EXPECT_EQ(cover::test::counted_allocations() - before, 0);
  EXPECT_EQ(errors, 0);
  EXPECT_EQ(prepared_ahead, 20);
}

}  // namespace
}  // namespace cover::sampc
