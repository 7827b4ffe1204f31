#include <gtest/gtest.h>

#include <cmath>

#include "cover/config/yaml_reader.hpp"
#include "cover/model/dynamics.hpp"
#include "cover/model/quaternion.hpp"
#include "cover/sampc/horizon_cost.hpp"
#include "cover/test/shipped_params.hpp"
#include "cover/vocabulary/angles.hpp"

namespace cover::sampc {
namespace {

using Eigen::Vector3d;
using model::Stage;

SampcInput example_input(Stage stage) {
  SampcInput in;
  in.stage = stage;
  in.uav_state = model::uav_state_at_rest(Vector3d(1.5, -2.0, 1.2));
  in.ugv.angular_velocity_rad_s = Vector3d(0.0, 0.0, 0.4);
  for (int k = 0; k <= kMaxHorizon; ++k) {
    in.reference.position_m[k] = Vector3d(1.5 - 0.05 * k, -2.0 + 0.08 * k, 1.2 + 0.01 * k);
    in.reference.velocity_m_s[k] = Vector3d(-0.5, 0.8, 0.1);
  }
  return in;
}

HorizonCost build(const SampcParams& params, const SampcInput& in, double held_yaw = 0.3) {
  HorizonCost cost;
  build_horizon_cost(params, in, held_yaw, cost);
  return cost;
}

TEST(HorizonCost, TrackingStagesFollowThePlanWithTable2Weights) {
  SampcParams params;
  params.tracking_feed_forward = false;  // Table 2's around-hover references
  for (Stage stage : {Stage::Initial, Stage::Final}) {
    const SampcInput in = example_input(stage);
    const HorizonCost cost = build(params, in);
    EXPECT_EQ(cost.reference_mode, ReferenceMode::XyzRef);
    for (int k = 0; k < params.horizon_steps; ++k) {
      const NodeCost& n = cost.nodes[k];
      const double decay = std::exp(-params.e0 * k);
      EXPECT_EQ(n.position_ref_m, in.reference.position_m[k]);
      EXPECT_EQ(n.velocity_ref_m_s, in.reference.velocity_m_s[k]);
      EXPECT_LT((n.position_weight - decay * Vector3d(200, 200, 300)).norm(), 1e-9);
      EXPECT_LT((n.velocity_weight - decay * Vector3d(100, 100, 300)).norm(), 1e-9);
      EXPECT_LT((n.attitude_weight - decay * Eigen::Vector4d::Constant(50)).norm(), 1e-9);
      EXPECT_LT((n.input_weight - std::exp(-params.e3 * k) * model::Input(1, 20, 20, 5)).norm(),
                1e-9);
      EXPECT_EQ(n.attitude_ref, Eigen::Vector4d(1, 0, 0, 0));
      EXPECT_EQ(n.squared_distance_weight, 0.0);
    }
    const NodeCost& terminal = cost.nodes[params.horizon_steps];
    EXPECT_EQ(terminal.input_weight, model::Input::Zero());
    EXPECT_NEAR(terminal.position_weight.z(),
                params.terminal_weight_scale * std::exp(-params.e0 * 20) * 300, 1e-9);
  }
}

TEST(HorizonCost, TransitionStageUsesXyZRefWithTheCustomisedVelocityAndYaw) {
  const SampcParams params;
  SampcInput in = example_input(Stage::Transition);
  // Already facing the UGV: the rate-limited yaw reference sits on its target at every node.
  in.uav_state.segment<4>(6) =
      model::yaw_quaternion(std::atan2(-in.uav_state(1), -in.uav_state(0)));
  const HorizonCost cost = build(params, in);
  EXPECT_EQ(cost.reference_mode, ReferenceMode::XyZRef);

  const Vector3d p = in.uav_state.head<3>();
  const double d0 = p.head<2>().squaredNorm();
  // Eq. 30: v_ref_xy = -(Omega x p)_xy - p_xy/|p_xy| * v0d, v0d the plan's horizontal speed.
  Vector3d expected_v0 = -in.ugv.angular_velocity_rad_s.cross(p);
  expected_v0.head<2>() -= p.head<2>().normalized() * in.reference.velocity_m_s[0].head<2>().norm();
  expected_v0.z() = in.reference.velocity_m_s[0].z();
  EXPECT_LT((cost.nodes[0].velocity_ref_m_s - expected_v0).norm(), 1e-12);
  EXPECT_LT((cost.nodes[0].velocity_weight - params.transition_weights.velocity).norm(), 1e-12);

  const double yaw = std::atan2(-p.y(), -p.x());
  EXPECT_NEAR(cost.yaw_ref_rad, yaw, 1e-12);
  for (int k = 0; k < params.horizon_steps; ++k) {
    const NodeCost& n = cost.nodes[k];
    const double decay = std::exp(-params.e0 * k);
    EXPECT_LT((n.position_weight - decay * Vector3d(0, 0, 200)).norm(), 1e-9);
    if (k > params.custom_velocity_nodes) {
      EXPECT_LT((n.velocity_weight - decay * Vector3d(0, 0, params.transition_weights.velocity.z()))
                    .norm(),
                1e-9);
      EXPECT_EQ(n.velocity_ref_m_s.z(), in.reference.velocity_m_s[k].z());
    }
    EXPECT_LT((n.attitude_weight - decay * Eigen::Vector4d::Constant(40)).norm(), 1e-9);
    EXPECT_LT((n.attitude_ref - model::yaw_quaternion(yaw)).norm(), 1e-12);
    EXPECT_NEAR(n.squared_distance_ref_m2, in.reference.position_m[k].head<2>().squaredNorm(),
                1e-12);
    EXPECT_NEAR(n.squared_distance_weight,
                std::exp(-params.e1 * k) * (200 * std::exp(params.e2_per_m2 * d0) + 100), 1e-9);
    EXPECT_LT((n.input_weight - std::exp(-params.e3 * k) * model::Input(1, 30, 30, 5)).norm(),
              1e-9);
  }
}

TEST(HorizonCost, DistanceWeightGrowsAsTheUavNearsTheUgv) {
  const SampcParams params;
  SampcInput far = example_input(Stage::Transition);
  SampcInput near = far;
  near.uav_state.head<2>() *= 0.2;
  EXPECT_GT(build(params, near).nodes[0].squared_distance_weight,
            build(params, far).nodes[0].squared_distance_weight);
}

TEST(HorizonCost, NoRefVxyDiffersFromCoverOnlyInTheHorizontalVelocityWeight) {
  SampcParams cover_params;
  SampcParams ablation = cover_params;
  ablation.mode = Mode::NoRefVxy;
  const SampcInput in = example_input(Stage::Transition);
  const HorizonCost a = build(cover_params, in), b = build(ablation, in);
  const double vertical = cover_params.transition_weights.velocity.z();
  EXPECT_EQ(b.nodes[0].velocity_weight, Vector3d(0, 0, vertical));
  // The customised velocity acts where the state is free: the first predicted node differs.
  EXPECT_EQ(a.nodes[1].velocity_weight.head<2>(),
            std::exp(-cover_params.e0) * Eigen::Vector2d(350, 350));
  EXPECT_EQ(b.nodes[1].velocity_weight, std::exp(-cover_params.e0) * Vector3d(0, 0, vertical));
  for (int k = 0; k <= cover_params.horizon_steps; ++k) {
    EXPECT_EQ(a.nodes[k].position_weight, b.nodes[k].position_weight);
    EXPECT_EQ(a.nodes[k].position_ref_m, b.nodes[k].position_ref_m);
    EXPECT_EQ(a.nodes[k].velocity_ref_m_s, b.nodes[k].velocity_ref_m_s);
    EXPECT_EQ(a.nodes[k].attitude_ref, b.nodes[k].attitude_ref);
    EXPECT_EQ(a.nodes[k].attitude_weight, b.nodes[k].attitude_weight);
    EXPECT_EQ(a.nodes[k].squared_distance_weight, b.nodes[k].squared_distance_weight);
    EXPECT_EQ(a.nodes[k].input_weight, b.nodes[k].input_weight);
    if (k > cover_params.custom_velocity_nodes) {
      EXPECT_EQ(a.nodes[k].velocity_weight, b.nodes[k].velocity_weight);
    }
  }
  // Outside the transition stage the ablation changes nothing.
  const HorizonCost c = build(cover_params, example_input(Stage::Final));
  const HorizonCost d = build(ablation, example_input(Stage::Final));
  EXPECT_EQ(c.nodes[0].velocity_weight, d.nodes[0].velocity_weight);
}

TEST(HorizonCost, ConiMpcTracksThePlanAtTheTransitionStageToo) {
  SampcParams coni;
  coni.mode = Mode::ConiMpc;
  SampcParams cover_params;
  cover_params.tracking_feed_forward = false;  // coni-mpc's transition never has it
  const HorizonCost at_transition = build(coni, example_input(Stage::Transition));
  const HorizonCost cover_initial = build(cover_params, example_input(Stage::Initial));
  EXPECT_EQ(at_transition.reference_mode, ReferenceMode::XyzRef);
  for (int k = 0; k <= coni.horizon_steps; ++k) {
    EXPECT_EQ(at_transition.nodes[k].position_weight, cover_initial.nodes[k].position_weight);
    EXPECT_EQ(at_transition.nodes[k].velocity_ref_m_s, cover_initial.nodes[k].velocity_ref_m_s);
    EXPECT_EQ(at_transition.nodes[k].attitude_ref, cover_initial.nodes[k].attitude_ref);
    EXPECT_EQ(at_transition.nodes[k].squared_distance_weight, 0.0);
    EXPECT_EQ(at_transition.nodes[k].input_ref, model::hover_input());
  }
}

// A plan accelerating at a constant rate (still UGV): the feed-forward references are a
// trajectory of the model itself. From node k's reference state under node k's input
// reference, one model step lands on node k + 1's reference.
TEST(HorizonCost, FeedForwardReferencesFlyThePlanInTheModel) {
  const SampcParams params;
  SampcInput in;
  in.stage = Stage::Final;
  const Vector3d p0(0.4, -0.3, 1.0), v0(-0.2, 0.1, -0.5), a(0.6, -0.3, 1.2);
  for (int k = 0; k <= kMaxHorizon; ++k) {
    const double t = k * params.step_s;
    in.reference.position_m[k] = p0 + v0 * t + 0.5 * a * t * t;
    in.reference.velocity_m_s[k] = v0 + a * t;
    in.reference.acceleration_m_s2[k] = a;
  }
  in.uav_state = model::uav_state_at_rest(p0);
  const HorizonCost cost = build(params, in);
  for (int k = 0; k + 1 < params.horizon_steps; ++k) {
    const NodeCost& n = cost.nodes[k];
    const Vector3d thrust = a + Vector3d(0.0, 0.0, model::kGravity_m_s2);
    EXPECT_NEAR(n.input_ref(0), thrust.norm(), 1e-9);
    EXPECT_LT((model::thrust_direction(n.attitude_ref) - thrust.normalized()).norm(), 1e-9);
    model::UavState x = model::UavState::Zero();
    x.segment<3>(0) = in.reference.position_m[k];
    x.segment<3>(3) = in.reference.velocity_m_s[k];
    x.segment<4>(6) = n.attitude_ref;
    const model::UavState next = model::uav_rk4_step(x, n.input_ref, in.ugv, params.step_s);
    EXPECT_LT((next.segment<3>(0) - in.reference.position_m[k + 1]).norm(), 1e-3) << k;
    EXPECT_LT((next.segment<3>(3) - in.reference.velocity_m_s[k + 1]).norm(), 1e-3) << k;
  }
}

// The rate references turn the yaw reference (0.8 rad/s toward the UGV's x axis) in a frame
// that itself turns at 0.4 rad/s: w_z = yaw' + Omega_z, and zero once the yaw is reached.
TEST(HorizonCost, RateFeedForwardFollowsTheYawReferenceInTheTurningFrame) {
  const SampcParams params;
  SampcInput in = example_input(Stage::Final);
  for (int k = 0; k <= kMaxHorizon; ++k) {
    in.reference.position_m[k] = Vector3d(0.0, 0.0, 1.0);
    in.reference.velocity_m_s[k] = Vector3d::Zero();
  }
  in.uav_state = model::uav_state_at_rest(Vector3d(0.0, 0.0, 1.0));
  in.uav_state.segment<4>(6) = model::yaw_quaternion(1.0);
  in.ugv.angular_velocity_rad_s = Vector3d(0.0, 0.0, 0.4);
  const HorizonCost cost = build(params, in);
  const double turn_rate = -params.yaw_reference_rate_rad_s;
  EXPECT_NEAR(cost.nodes[0].input_ref(3), turn_rate + 0.4, 0.02);
  EXPECT_NEAR(cost.nodes[params.horizon_steps - 1].input_ref(3), 0.4, 0.02);
  // A level hover in the turning frame: its thrust and no roll or pitch rate.
  EXPECT_LT(std::abs(cost.nodes[0].input_ref(1)) + std::abs(cost.nodes[0].input_ref(2)), 0.05);
}

TEST(HorizonCost, YawIsHeldOnTheUgvAxis) {
  const SampcParams params;
  SampcInput in = example_input(Stage::Transition);
  in.uav_state.head<2>() = Eigen::Vector2d(0.01, 0.0);
  const HorizonCost cost = build(params, in, 0.7);
  EXPECT_NEAR(cost.yaw_ref_rad, 0.7, 1e-12);
  EXPECT_TRUE(cost.nodes[0].velocity_ref_m_s.allFinite());
}

TEST(HorizonCost, CustomisedVelocityIsOnTheFirstFreeNodes) {
  SampcParams params;
  params.custom_velocity_nodes = 3;
  params.eq30_acceleration_limit_m_s2 = 0.0;  // eq. 30 itself at every node
  const SampcInput in = example_input(Stage::Transition);
  const HorizonCost cost = build(params, in);
  for (int k = 1; k <= 3; ++k) {
    EXPECT_EQ(cost.nodes[k].velocity_ref_m_s.head<2>(), cost.nodes[0].velocity_ref_m_s.head<2>());
    EXPECT_GT(cost.nodes[k].velocity_weight.x(), 0.0);
  }
  EXPECT_EQ(cost.nodes[4].velocity_weight.head<2>(), Eigen::Vector2d::Zero());
}

// Eq. 30 is a velocity at a position: given the warm start, a free node takes it at its own
// predicted position, with the plan's speed now (v0d).
TEST(HorizonCost, FreeNodesTakeEq30AtTheirPredictedPosition) {
  SampcParams params;
  params.custom_velocity_nodes = 2;
  params.eq30_acceleration_limit_m_s2 = 0.0;  // eq. 30 itself at every node
  const SampcInput in = example_input(Stage::Transition);
  std::array<model::UavState, kMaxHorizon + 1> predicted;
  for (int k = 0; k <= kMaxHorizon; ++k) {
    predicted[k] = model::uav_state_at_rest(Vector3d(1.5 - 0.3 * k, -2.0 + 0.5 * k, 1.2));
  }
  HorizonCost cost;
  build_horizon_cost(params, in, 0.3, cost, {}, 0.0, predicted.data());
  const Vector3d omega = in.ugv.angular_velocity_rad_s;
  const double speed = in.reference.velocity_m_s[0].head<2>().norm();
  for (int k = 1; k <= 2; ++k) {
    const Vector3d p = predicted[k].segment<3>(model::idx::kPosition);
    const Eigen::Vector2d expected =
        -omega.cross(p).head<2>() - p.head<2>() / p.head<2>().norm() * speed;
    EXPECT_LT((cost.nodes[k].velocity_ref_m_s.head<2>() - expected).norm(), 1e-12) << k;
  }
  // Node 0 is the measurement itself.
  const HorizonCost without = build(params, in);
  EXPECT_EQ(cost.nodes[0].velocity_ref_m_s, without.nodes[0].velocity_ref_m_s);
  EXPECT_NE(cost.nodes[1].velocity_ref_m_s, without.nodes[1].velocity_ref_m_s);
}

// The UAV at rest, eq. 30 asking for ~1.5 m/s: node k's reference is at most limit * k dt
// from the UAV's velocity relative to the UGV's translation, and eq. 30 once that reaches it.
TEST(HorizonCost, Eq30ReferenceAsksOnlyForAReachableChange) {
  SampcParams params;
  params.custom_velocity_nodes = 20;
  params.eq30_acceleration_limit_m_s2 = 2.0;
  const SampcInput in = example_input(Stage::Transition);
  SampcParams unlimited = params;
  unlimited.eq30_acceleration_limit_m_s2 = 0.0;
  const HorizonCost cost = build(params, in);
  const HorizonCost law = build(unlimited, in);
  const Vector3d omega = in.ugv.angular_velocity_rad_s;
  const Vector3d p = in.uav_state.head<3>();
  const Eigen::Vector2d now = (in.uav_state.segment<3>(3) + omega.cross(p)).head<2>();
  EXPECT_EQ(cost.nodes[0].velocity_ref_m_s, law.nodes[0].velocity_ref_m_s);
  bool limited_somewhere = false;
  bool reached_somewhere = false;
  for (int k = 1; k <= params.custom_velocity_nodes; ++k) {
    const Eigen::Vector2d relative =
        cost.nodes[k].velocity_ref_m_s.head<2>() + omega.cross(p).head<2>();
    const double change = (relative - now).norm();
    EXPECT_LE(change, 2.0 * k * params.step_s + 1e-12) << k;
    const double to_law = (cost.nodes[k].velocity_ref_m_s - law.nodes[k].velocity_ref_m_s).norm();
    limited_somewhere |= to_law > 1e-3;
    reached_somewhere |= to_law < 1e-12;
  }
  EXPECT_TRUE(limited_somewhere);
  EXPECT_TRUE(reached_somewhere);
}

// After a frame switch the target yaw can be 180 deg from the UAV's: the reference must
// turn toward it at the configured rate from the measured yaw, never jump.
TEST(HorizonCost, YawReferenceIsRateLimitedFromTheMeasuredYaw) {
  const SampcParams params;
  for (Stage stage : {Stage::Transition, Stage::Final}) {
    SampcInput in = example_input(stage);
    const double target =
        stage == Stage::Transition ? std::atan2(-in.uav_state(1), -in.uav_state(0)) : 0.0;
    const double start = target + 3.1;  // nearly opposite
    in.uav_state.segment<4>(6) = model::yaw_quaternion(start);
    const HorizonCost cost = build(params, in);
    double previous = start;
    for (int k = 0; k <= params.horizon_steps; ++k) {
      const Eigen::Vector4d& r = cost.nodes[k].attitude_ref;
      const double yaw = 2.0 * std::atan2(r(3), r(0));
      const double step = std::remainder(yaw - previous, model::kTwoPi);
      EXPECT_LE(std::abs(step), params.yaw_reference_rate_rad_s * params.step_s + 1e-9) << k;
      if (k > 0) {
        EXPECT_LT(step, 0.0) << "turns the short way round, k = " << k;
      }
      previous = yaw;
    }
    EXPECT_NEAR(std::remainder(previous - start, model::kTwoPi),
                -params.yaw_reference_rate_rad_s * params.step_s * params.horizon_steps, 1e-9);
  }
}

TEST(HorizonCost, AttitudeCostIsSignInvariant) {
  const SampcParams params;
  const HorizonCost cost = build(params, example_input(Stage::Transition));
  model::UavState x = example_input(Stage::Transition).uav_state;
  x.segment<4>(6) = Eigen::Vector4d(0.8, 0.1, -0.3, 0.5).normalized();
  model::UavState flipped = x;
  flipped.segment<4>(6) *= -1.0;
  EXPECT_NEAR(cost.nodes[3].evaluate(x, model::hover_input()),
              cost.nodes[3].evaluate(flipped, model::hover_input()), 1e-12);
}

// Every field (SampcParams::fields, the weight sets' and intercept's by dotted keys), shipped
// with its default value.
TEST(SampcParams, ShippedConfigLoadsAndEqualsTheDefaults) {
  const std::string path = config::default_config_dir() + "/sampc.yaml";
  cover::test::expect_shipped_file_holds_defaults(SampcParams::load_file(path), path, "sampc");
}

TEST(SampcParams, RejectsBadValuesNamingTheKey) {
  const auto load = [](const std::string& text) {
    config::YamlReader reader(YAML::Load(text), "test:sampc");
    return SampcParams::load(reader);
  };
  EXPECT_NO_THROW(load("mode: coni-mpc"));
  EXPECT_THROW(load("mode: fancy"), config::ConfigError);
  EXPECT_THROW(load("horizn_steps: 10"), config::ConfigError);
  try {
    load("e2_per_m2: 0.5");
    FAIL();
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("e2_per_m2"), std::string::npos);
  }
  EXPECT_THROW(load("tracking_weights: {input: [1, 0, 20, 5]}"), config::ConfigError);
  EXPECT_THROW(load("thrust_max_m_s2: 9.0"), config::ConfigError);
  EXPECT_THROW(load("yaw_reference_rate_rad_s: 2.0"), config::ConfigError);  // > yaw rate bound
  EXPECT_THROW(load("custom_velocity_nodes: 0"), config::ConfigError);
  EXPECT_THROW(load("eq30_acceleration_limit_m_s2: -1"), config::ConfigError);
  EXPECT_THROW(load("frame_switch_iterations: 0"), config::ConfigError);
  EXPECT_THROW(load("switch_smoothing_s: -0.1"), config::ConfigError);
  EXPECT_THROW(load("switch_input_rate_weight: [0, -1, 0, 0]"), config::ConfigError);
  EXPECT_THROW(load("transition_input_rate_weight: [0, 0, .nan, 0]"), config::ConfigError);
}

}  // namespace
}  // namespace cover::sampc
