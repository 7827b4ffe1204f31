#include <gtest/gtest.h>

#include "cover/model/dynamics.hpp"
#include "cover/model/quaternion.hpp"

namespace cover::model {
namespace {

using Eigen::Vector3d;

TEST(ModelDynamics, HoverIsAnEquilibriumWithTheUgvAtRest) {
  const UavState uav = uav_state_at_rest(Vector3d(0.3, -0.2, 1.5));
  const State x = make_state(uav, UgvMotion::at_rest());
  EXPECT_LT(dynamics(x, hover_input()).norm(), 1e-12);
  EXPECT_LT(uav_dynamics(uav, hover_input(), UgvMotion::at_rest()).norm(), 1e-12);
  EXPECT_LT((rk4_step(x, hover_input(), 0.1) - x).norm(), 1e-12);
  EXPECT_LT((uav_rk4_step(uav, hover_input(), UgvMotion::at_rest(), 0.1) - uav).norm(), 1e-12);
}

TEST(ModelDynamics, MoreThrustThanGravityAcceleratesUp) {
  const UavState uav = uav_state_at_rest(Vector3d::Zero());
  Input u = hover_input();
  u(input_idx::kThrust) += 1.0;
  const UavState dx = uav_dynamics(uav, u, UgvMotion::at_rest());
  EXPECT_NEAR(dx(idx::kVelocity + 2), 1.0, 1e-12);
}

TEST(ModelDynamics, UavModelMatchesTheFullModel) {
  UgvMotion ugv;
  ugv.specific_force_m_s2 = Vector3d(0.4, -0.3, 9.9);
  ugv.angular_velocity_rad_s = Vector3d(0.05, -0.02, 0.6);
  ugv.angular_acceleration_rad_s2 = Vector3d(0.01, 0.02, -0.3);
  UavState uav;
  uav << 1.0, -2.0, 1.2, 0.3, 0.1, -0.2, 0.0, 0.0, 0.0, 0.0;
  uav.segment<4>(idx::kQuaternion) = Eigen::Vector4d(0.9, 0.1, -0.2, 0.3).normalized();
  const Input u(10.5, 0.4, -0.3, 0.2);
  const State full_next = rk4_step(make_state(uav, ugv), u, 0.1);
  const UavState uav_next = uav_rk4_step(uav, u, ugv, 0.1);
  EXPECT_LT((full_next.head<kUavStateSize>() - uav_next).norm(), 1e-12);
  // Omega integrates beta; a and beta stay.
  EXPECT_LT((ugv_part(full_next).angular_velocity_rad_s - ugv.advanced(0.1).angular_velocity_rad_s)
                .norm(),
            1e-12);
  EXPECT_NEAR(full_next.segment<4>(idx::kQuaternion).norm(), 1.0, 1e-12);
}

// Ground truth in the inertial world frame W: a UAV and a UGV that rotates about all axes
// with constant angular acceleration while its accelerometer reads a constant force.
struct WorldState {
  Vector3d uav_position, uav_velocity;
  Eigen::Vector4d uav_attitude;  // A in W
  Vector3d ugv_position, ugv_velocity;
  Eigen::Vector4d ugv_attitude;  // G in W
  Vector3d ugv_rate;             // Omega, in G
};

struct WorldDerivative {
  Vector3d dp, dv;
  Eigen::Vector4d dq;
  Vector3d dr, ds;
  Eigen::Vector4d dqg;
  Vector3d dw;
};

WorldDerivative world_derivative(const WorldState& s, const Input& u,
                                 const Vector3d& specific_force, const Vector3d& beta) {
  const Vector3d gravity(0.0, 0.0, -kGravity_m_s2);
  WorldDerivative d;
  d.dp = s.uav_velocity;
  d.dv = rotation_matrix(s.uav_attitude) * Vector3d(0, 0, u(0)) + gravity;
  d.dq = 0.5 * multiply(s.uav_attitude, Eigen::Vector4d(0, u(1), u(2), u(3)));
  d.dr = s.ugv_velocity;
  d.ds = rotation_matrix(s.ugv_attitude) * specific_force + gravity;
  d.dqg = 0.5 * multiply(s.ugv_attitude,
                         Eigen::Vector4d(0, s.ugv_rate.x(), s.ugv_rate.y(), s.ugv_rate.z()));
  d.dw = beta;
  return d;
}

WorldState add(const WorldState& s, const WorldDerivative& d, double h) {
  return {s.uav_position + h * d.dp, s.uav_velocity + h * d.dv, s.uav_attitude + h * d.dq,
          s.ugv_position + h * d.dr, s.ugv_velocity + h * d.ds, s.ugv_attitude + h * d.dqg,
          s.ugv_rate + h * d.dw};
}

WorldState world_rk4(const WorldState& s, const Input& u, const Vector3d& a, const Vector3d& beta,
                     double h) {
  const WorldDerivative k1 = world_derivative(s, u, a, beta);
  const WorldDerivative k2 = world_derivative(add(s, k1, h / 2), u, a, beta);
  const WorldDerivative k3 = world_derivative(add(s, k2, h / 2), u, a, beta);
  const WorldDerivative k4 = world_derivative(add(s, k3, h), u, a, beta);
  WorldState next = add(add(add(add(s, k1, h / 6), k2, h / 3), k3, h / 3), k4, h / 6);
  next.uav_attitude.normalize();
  next.ugv_attitude.normalize();
  return next;
}

// p = R_G^T (P - r), v = R_G^T (V - s) - Omega x p, q = q_G^-1 (x) q_A.
UavState to_ugv_frame(const WorldState& s) {
  const Eigen::Matrix3d r_gt = rotation_matrix(s.ugv_attitude).transpose();
  UavState x;
  const Vector3d p = r_gt * (s.uav_position - s.ugv_position);
  x.segment<3>(idx::kPosition) = p;
  x.segment<3>(idx::kVelocity) = r_gt * (s.uav_velocity - s.ugv_velocity) - s.ugv_rate.cross(p);
  const Eigen::Vector4d ugv_inverse(s.ugv_attitude(0), -s.ugv_attitude(1), -s.ugv_attitude(2),
                                    -s.ugv_attitude(3));
  x.segment<4>(idx::kQuaternion) = multiply(ugv_inverse, s.uav_attitude);
  return x;
}

TEST(ModelDynamics, AgreesWithWorldFrameIntegrationForARotatingAcceleratingUgv) {
  const Vector3d specific_force(0.8, -0.5, 10.3);
  const Vector3d beta(0.05, -0.08, 0.25);
  WorldState world;
  world.uav_position = Vector3d(1.0, 2.0, 1.5);
  world.uav_velocity = Vector3d(0.4, -0.3, 0.1);
  world.uav_attitude = Eigen::Vector4d(0.95, 0.05, -0.1, 0.2).normalized();
  world.ugv_position = Vector3d(-0.5, 0.3, 0.0);
  world.ugv_velocity = Vector3d(0.6, 0.2, 0.0);
  world.ugv_attitude = yaw_quaternion(0.7);
  world.ugv_rate = Vector3d(0.02, -0.03, 0.4);

  UgvMotion ugv;
  ugv.specific_force_m_s2 = specific_force;
  ugv.angular_velocity_rad_s = world.ugv_rate;
  ugv.angular_acceleration_rad_s2 = beta;
  const UavState initial = to_ugv_frame(world);
  State model = make_state(initial, ugv);

  // Piecewise-constant inputs that exercise every channel.
  const double control_period_s = 0.1;
  const int world_substeps = 50;
  for (int step = 0; step < 20; ++step) {
    const double t = step * control_period_s;
    const Input u(9.81 + 1.5 * std::sin(2.0 * t), 0.6 * std::cos(3.0 * t), -0.5 * std::sin(t),
                  0.3 * std::cos(1.3 * t));
    for (int i = 0; i < world_substeps; ++i) {
      world = world_rk4(world, u, specific_force, beta, control_period_s / world_substeps);
    }
    model = rk4_step(model, u, control_period_s);
  }

  const UavState expected = to_ugv_frame(world);
  const UavState actual = uav_part(model);
  EXPECT_LT((actual.head<3>() - expected.head<3>()).norm(), 1e-4);
  EXPECT_LT((actual.segment<3>(3) - expected.segment<3>(3)).norm(), 1e-4);
  const Eigen::Vector4d q_actual = actual.segment<4>(6), q_expected = expected.segment<4>(6);
  EXPECT_GT(std::abs(q_actual.dot(q_expected)), 1.0 - 1e-8);
  EXPECT_LT((ugv_part(model).angular_velocity_rad_s - world.ugv_rate).norm(), 1e-9);
  // The UAV actually moved relative to the UGV: the comparison is not trivially satisfied.
  EXPECT_GT((actual.head<3>() - initial.head<3>()).norm(), 0.5);
}

TEST(ModelDynamics, TranslationalVelocityRemovesTheRotationInducedPart) {
  UgvMotion ugv;
  ugv.angular_velocity_rad_s = Vector3d(0, 0, 0.5);
  // A UAV hovering still in the world above a spinning UGV appears to circle in G_k.
  UavState x = uav_state_at_rest(Vector3d(2.0, 0.0, 1.0));
  x.segment<3>(idx::kVelocity) = -ugv.angular_velocity_rad_s.cross(Vector3d(2.0, 0.0, 1.0));
  EXPECT_LT(translational_velocity(x, ugv).norm(), 1e-12);
}

}  // namespace
}  // namespace cover::model
