#include "cover/mission/disturbance_observer.hpp"

#include <gtest/gtest.h>

#include <random>

namespace cover::mission {
namespace {

using Eigen::Vector3d;

// The "true" plant: the model plus a constant unmodelled acceleration (drag, heavier UAV),
// with the simulator's 1 cm/s velocity noise on the measurement.
struct Plant {
  model::UavState state = model::uav_state_at_rest(Vector3d(0.5, -0.3, 1.2));
  model::UgvMotion ugv;
  Vector3d missing_m_s2{0.25, -0.15, -0.45};

  void step(const model::Input& u, double dt) {
    model::UgvMotion true_ugv = ugv;
    true_ugv.specific_force_m_s2 -= missing_m_s2;  // v' gains + missing
    state = model::uav_rk4_step(state, u, true_ugv, dt);
  }
};

TEST(DisturbanceObserver, LearnsAConstantMissingAccelerationThroughNoise) {
  constexpr double dt = 0.01;
  DisturbanceObserver observer(50, dt, 0.5);
  Plant plant;
  plant.ugv.angular_velocity_rad_s = Vector3d(0.0, 0.0, 0.3);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  const model::Input command(model::kGravity_m_s2 + 0.2, 0.05, -0.03, 0.1);
  for (int step = 0; step < 600; ++step) {
    model::UavState measured = plant.state;
    for (int i = 3; i < 6; ++i) measured(i) += noise(rng);
    // The model sees the UGV with the current estimate subtracted, as SAMPC does.
    model::UgvMotion seen = plant.ugv;
    seen.specific_force_m_s2 -= observer.estimate_m_s2();
    observer.update(measured, seen, command);
    plant.step(command, dt);
  }
  ASSERT_TRUE(observer.ready());
  EXPECT_LT((observer.estimate_m_s2() - plant.missing_m_s2).cwiseAbs().maxCoeff(), 0.05);
}

TEST(DisturbanceObserver, NothingMissingEstimatesZeroAndResetClears) {
  constexpr double dt = 0.01;
  DisturbanceObserver observer(20, dt, 0.3);
  Plant plant;
  plant.missing_m_s2.setZero();
  const model::Input hover = model::hover_input();
  for (int step = 0; step < 19; ++step) {
    observer.update(plant.state, plant.ugv, hover);
    plant.step(hover, dt);
  }
  EXPECT_FALSE(observer.ready()) << "needs a full window";
  for (int step = 0; step < 200; ++step) {
    observer.update(plant.state, plant.ugv, hover);
    plant.step(hover, dt);
  }
  EXPECT_TRUE(observer.ready());
  EXPECT_LT(observer.estimate_m_s2().norm(), 1e-9);
  model::UavState bad = plant.state;
  bad(3) = std::nan("");
  observer.update(bad, plant.ugv, hover);  // a corrupt sample restarts the window
  EXPECT_FALSE(observer.ready());
  EXPECT_EQ(observer.estimate_m_s2(), Vector3d::Zero());
}

}  // namespace
}  // namespace cover::mission
