#include <gtest/gtest.h>

#include "cover/sim/world.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

// The controller's model (docs/model.md, eqs. 3-8) written independently of the simulator:
//   v' = -beta x p - 2 Omega x v - Omega x (Omega x p) + R(q) [0, 0, F] - a
//   q' = 1/2 q (x) [0, w] - 1/2 [0, Omega] (x) q
// The simulator's relative states and IMU truth must satisfy it when the plant has no
// drag (F being the plant's actual specific thrust). This pins the frame conventions
// shared by the simulator and the controller.
TEST(ModelConsistency, RelativeStatesObeyTheNonInertialModel) {
  UgvMotionPatternParams eight;
  eight.kind = MotionPatternKind::FigureEight;
  eight.speed_m_s = 0.8;
  eight.half_length_m = 2.0;
  eight.half_width_m = 1.0;
  eight.phase_rad = 0.4;
  WorldParams params = test::noiseless_world({eight});
  params.uav.drag_coefficients_1_s.setZero();
  params.uav_initial.start_on_ugv = -1;
  params.uav_initial.position_m = {1.0, -1.5, 2.0};
  World world(params);

  QuadrotorCommand command;
  command.thrust_m_s2 = 10.5;
  command.body_rate_rad_s = Vec3(0.4, -0.3, 0.6);
  world.advance(command, 0.5);  // rate loop and thrust lag settle

  const double dt = world.physics_dt_s();
  for (int trial = 0; trial < 5; ++trial) {
    world.advance(command, 0.2);
    const RelativeState before = world.true_relative_state(0);
    world.step(command);
    const RelativeState now = world.true_relative_state(0);
    const WorldState state = world.state();
    world.step(command);
    const RelativeState after = world.true_relative_state(0);

    const UgvState& ugv = state.ugvs[0];
    const Eigen::Vector3d a =
        true_imu_sample(ugv, params.gravity_m_s2, state.time_s).specific_force_m_s2;
    const Eigen::Vector3d omega = ugv.angular_velocity_in_body_rad_s();
    const Eigen::Vector3d beta = ugv.angular_acceleration_in_body_rad_s2();
    const double thrust = state.uav.thrust_n / params.uav.mass_true_kg;
    const Eigen::Vector3d& p = now.position_m;
    const Eigen::Vector3d& v = now.velocity_m_s;

    const Eigen::Vector3d v_dot_model = -beta.cross(p) - 2.0 * omega.cross(v) -
                                        omega.cross(omega.cross(p)) +
                                        now.attitude * Eigen::Vector3d(0, 0, thrust) - a;
    // the frame really rotates and accelerates, so every term of the model is exercised
    EXPECT_GT((2.0 * omega.cross(v)).norm(), 0.05);
    EXPECT_GT(beta.norm(), 0.01);
    const Eigen::Vector3d v_dot_sim = (after.velocity_m_s - before.velocity_m_s) / (2 * dt);
    EXPECT_LT((v_dot_model - v_dot_sim).norm(), 1e-3) << "trial " << trial;

    const Eigen::Vector3d w = state.uav.body_rate_rad_s.eigen();
    const Eigen::Quaterniond q = now.attitude;
    const Eigen::Quaterniond body_term = q * Eigen::Quaterniond(0, w.x(), w.y(), w.z());
    const Eigen::Quaterniond frame_term =
        Eigen::Quaterniond(0, omega.x(), omega.y(), omega.z()) * q;
    const Eigen::Vector4d q_dot_model = 0.5 * (body_term.coeffs() - frame_term.coeffs());
    const Eigen::Vector4d q_dot_sim =
        (after.attitude.coeffs() - before.attitude.coeffs()) / (2 * dt);
    EXPECT_LT((q_dot_model - q_dot_sim).norm(), 1e-3) << "trial " << trial;
  }
}

}  // namespace
}  // namespace cover::sim
