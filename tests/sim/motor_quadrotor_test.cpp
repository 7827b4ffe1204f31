// The motor-level quadrotor against hand-worked cases: hover, a pure yaw torque, a roll
// torque from the arm length, a motor step, a vehicle resting on a moving deck.
#include "cover/sim/motor_quadrotor.hpp"

#include "cover/sim/firmware_uav_params.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "cover/config/yaml_reader.hpp"
#include "cover/sim/surface_contact.hpp"
#include "cover/sim/uav_sensor_suite.hpp"
#include "cover/sim/world.hpp"
#include "cover/test/shipped_params.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 0.001;  // the world's 1 kHz physics step

std::string config_file(const char* name) {
  return config::default_config_dir() + "/sim/" + name;
}

MotorQuadrotorParams arducopter() {
  return FirmwareUavParams::load_file(config_file("firmware_uav_arducopter.yaml"), 1000.0).plant;
}

MotorQuadrotorState in_mid_air(const MotorQuadrotor& plant, const MotorOutputs& outputs) {
  MotorQuadrotorState s;
  s.body.position_m = Vec3(0.0, 0.0, 10.0);
  s.rotor_speed_rad_s = plant.steady_rotor_speeds(outputs);
  return s;
}

// Rotor speeds giving these thrusts: w = sqrt(T / k_T).
std::array<double, kRotorCount> speeds_for(const MotorQuadrotor& plant,
                                           const std::array<double, kRotorCount>& thrust_n) {
  std::array<double, kRotorCount> w{};
  for (int i = 0; i < kRotorCount; ++i) {
    w[i] = std::sqrt(thrust_n[i] / plant.motor().thrust_coefficient_n_s2());
  }
  return w;
}

// Outputs whose steady thrust is `thrust_n` on each motor (the curve inverted).
MotorOutputs outputs_for(const MotorQuadrotor& plant,
                         const std::array<double, kRotorCount>& thrust_n) {
  MotorOutputs u{};
  for (int i = 0; i < kRotorCount; ++i) {
    u[i] = plant.motor().output_for_fraction(thrust_n[i] / plant.params().motor.max_thrust_n);
  }
  return u;
}

TEST(MotorQuadrotor, Px4HoverOutputIsWeightOverMaximumThrust) {
  const MotorQuadrotor plant(MotorQuadrotorParams{});
  // Linear curve: u = m g / (4 T_max) = 1.05 * 9.81 / 20.
  EXPECT_NEAR(plant.hover_output(0.0, kG), 0.515025, 1e-12);
  // k_T = 5 / 1100^2; hover speed = 1100 sqrt(0.515025) = 789.4175 rad/s.
  EXPECT_NEAR(plant.steady_rotor_speeds({0.515025, 0.515025, 0.515025, 0.515025})[0], 789.4175,
              1e-3);
}

TEST(MotorQuadrotor, ArduCopterHoverOutputInvertsItsExpoCurve) {
  const MotorQuadrotor plant(arducopter());
  // f = 0.515025 = 0.35 r + 0.65 r^2 -> r = (-0.35 + sqrt(0.1225 + 2.6 f)) / 1.3 = 0.660732;
  // u = 0.15 + 0.8 r = 0.678586.
  const double u = plant.hover_output(0.0, kG);
  EXPECT_NEAR(u, 0.678586, 1e-6);
  EXPECT_NEAR(plant.motor().thrust_fraction(u), 0.515025, 1e-12);
  EXPECT_EQ(plant.motor().thrust_fraction(0.15), 0.0);  // MOT_SPIN_MIN: no thrust yet
  EXPECT_EQ(plant.motor().thrust_fraction(0.95), 1.0);  // MOT_SPIN_MAX: all of it
  EXPECT_EQ(plant.motor().thrust_fraction(1.0), 1.0);
}

TEST(MotorQuadrotor, AllMotorsAtTheHoverOutputHoldTheVehicleStill) {
  for (const MotorQuadrotorParams& params : {MotorQuadrotorParams{}, arducopter()}) {
    const MotorQuadrotor plant(params);
    const double u = plant.hover_output(0.0, kG);
    const MotorOutputs outputs{u, u, u, u};
    MotorQuadrotorState s = in_mid_air(plant, outputs);
    // The PX4 iris's arms are not symmetric front/back in y, but they balance: sum y_i = 0.
    EXPECT_LT(plant.linear_acceleration_m_s2(s, 0.0, kG).norm(), 1e-12);
    EXPECT_LT(plant.angular_acceleration_rad_s2(s).norm(), 1e-12);
    for (int i = 0; i < 1000; ++i) plant.step(s, outputs, 0.0, kG, kDt);
    EXPECT_LT((s.body.position_m.eigen() - Eigen::Vector3d(0, 0, 10)).norm(), 1e-9);
    EXPECT_LT(s.body.velocity_m_s.eigen().norm(), 1e-9);
    EXPECT_LT(s.body.body_rate_rad_s.eigen().norm(), 1e-9);
    EXPECT_NEAR(s.body.thrust_n, 1.05 * kG, 1e-9);
  }
}

TEST(MotorQuadrotor, DiagonalPairsUpAndDownGiveAPureYawTorque) {
  // ArduCopter's symmetric quad X: motors 1, 2 turn CCW, 3, 4 CW. Thrusts T + d on the CCW
  // pair and T - d on the CW pair: force 4 T unchanged, no roll or pitch (the pairs are
  // diagonal), and yaw torque -k (2 (T + d)) + k (2 (T - d)) = -4 k d (a CCW rotor pushes
  // the body clockwise). k = 0.05 m, d = 0.5 N: -0.1 N m; / Izz 0.0386575 = -2.586820 rad/s^2.
  const MotorQuadrotor plant(arducopter());
  const double hover_n = 1.05 * kG / 4.0;
  const double d = 0.5;
  const std::array<double, kRotorCount> thrust{hover_n + d, hover_n + d, hover_n - d, hover_n - d};
  MotorQuadrotorState s;
  s.body.position_m = Vec3(0.0, 0.0, 10.0);
  s.rotor_speed_rad_s = speeds_for(plant, thrust);
  const BodyWrench wrench = plant.wrench(s);
  EXPECT_NEAR(wrench.force_n.z(), 1.05 * kG, 1e-12);
  EXPECT_NEAR(wrench.torque_n_m.x(), 0.0, 1e-12);
  EXPECT_NEAR(wrench.torque_n_m.y(), 0.0, 1e-12);
  EXPECT_NEAR(wrench.torque_n_m.z(), -0.1, 1e-12);
  const double yaw_acceleration = -0.1 / 0.0386575;  // -2.586820
  EXPECT_NEAR(plant.angular_acceleration_rad_s2(s).z(), yaw_acceleration, 1e-9);

  // Flown with the outputs of those thrusts: the yaw rate ramps, nothing else moves
  // (w along a principal axis: no gyroscopic coupling; thrust stays vertical).
  const MotorOutputs outputs = outputs_for(plant, thrust);
  for (int i = 0; i < 100; ++i) plant.step(s, outputs, 0.0, kG, kDt);
  EXPECT_NEAR(s.body.body_rate_rad_s.z, yaw_acceleration * 0.1, 1e-9);
  EXPECT_LT(std::abs(s.body.body_rate_rad_s.x) + std::abs(s.body.body_rate_rad_s.y), 1e-12);
  EXPECT_LT(s.body.velocity_m_s.eigen().norm(), 1e-9);
  // yaw = 1/2 alpha t^2 = -0.0129341 rad
  const Eigen::Matrix3d r = s.body.attitude.eigen().toRotationMatrix();
  EXPECT_NEAR(std::atan2(r(1, 0), r(0, 0)), 0.5 * yaw_acceleration * 0.01, 1e-9);
}

TEST(MotorQuadrotor, Px4IrisYawInputFollowsTheSihSignAndCouplesIntoRollByItsArms) {
  // PX4 SIH: M_yaw(FRD) = Q (u0 + u1 - u2 - u3): the CCW pair up turns the nose right,
  // i.e. negative yaw about FLU z. The iris's rear arms are shorter (y 0.1875 vs 0.245), so
  // the diagonal pairs also roll: tau_x = d (-0.245 + 0.1875 - 0.245 + 0.1875) = -0.115 d.
  const MotorQuadrotor plant(MotorQuadrotorParams{});
  const double hover_n = 1.05 * kG / 4.0;
  const double d = 0.5;
  MotorQuadrotorState s;
  s.rotor_speed_rad_s = speeds_for(plant, {hover_n + d, hover_n + d, hover_n - d, hover_n - d});
  const BodyWrench wrench = plant.wrench(s);
  EXPECT_NEAR(wrench.torque_n_m.z(), -4.0 * 0.05 * d, 1e-12);
  EXPECT_NEAR(wrench.torque_n_m.x(), -0.115 * d, 1e-12);
  EXPECT_NEAR(wrench.torque_n_m.y(), 0.0, 1e-12);
}

TEST(MotorQuadrotor, LeftRightDifferenceRollsByTheArmLength) {
  // ArduCopter quad X, arm 0.25 m at 45 deg: |y| = 0.176777 m. Left rotors (3 front left,
  // 2 rear left) T + d, right (1, 4) T - d: tau_x = 4 * 0.176777 * d = 0.353554 N m for
  // d = 0.5 N; alpha_x = 0.353554 / 0.0203875 = 17.34170 rad/s^2; no yaw (each spin pair has
  // one up, one down), no pitch.
  const MotorQuadrotor plant(arducopter());
  const double hover_n = 1.05 * kG / 4.0;
  const double d = 0.5;
  MotorQuadrotorState s;
  s.rotor_speed_rad_s = speeds_for(plant, {hover_n - d, hover_n + d, hover_n + d, hover_n - d});
  const BodyWrench wrench = plant.wrench(s);
  EXPECT_NEAR(wrench.torque_n_m.x(), 4.0 * 0.176777 * d, 1e-12);
  EXPECT_NEAR(wrench.torque_n_m.y(), 0.0, 1e-12);
  EXPECT_NEAR(wrench.torque_n_m.z(), 0.0, 1e-12);
  const Eigen::Vector3d alpha = plant.angular_acceleration_rad_s2(s);
  EXPECT_NEAR(alpha.x(), 17.34170, 1e-4);
  EXPECT_NEAR(alpha.y(), 0.0, 1e-12);
  EXPECT_NEAR(alpha.z(), 0.0, 1e-12);
  // Positive roll about FLU x: the left side (stronger rotors) goes up.
}

TEST(MotorQuadrotor, RotorSpeedFollowsTheFirstOrderStep) {
  // From standstill, output 1: w(t) = w_max (1 - exp(-t / tau)), tau 0.02 s, w_max 1100:
  // 63.2 % (695.3327 rad/s) at tau, 95.0 % (1045.2342) at 3 tau.
  const MotorQuadrotor plant(MotorQuadrotorParams{});
  MotorQuadrotorState s;
  s.body.position_m = Vec3(0.0, 0.0, 10.0);
  const MotorOutputs full{1.0, 1.0, 1.0, 1.0};
  for (int i = 1; i <= 60; ++i) {
    plant.step(s, full, 0.0, kG, kDt);
    const double expected = 1100.0 * (1.0 - std::exp(-i * kDt / 0.02));
    for (double w : s.rotor_speed_rad_s) ASSERT_NEAR(w, expected, 1e-4) << "step " << i;
    if (i == 20) EXPECT_NEAR(s.rotor_speed_rad_s[0], 695.3327, 1e-3);
    if (i == 60) EXPECT_NEAR(s.rotor_speed_rad_s[0], 1045.2342, 1e-3);
  }
  // Thrust is k_T w^2, not a lag of its own: at tau it is 0.632^2 = 40 % of 20 N.
  EXPECT_NEAR(s.body.thrust_n, 20.0 * std::pow(1.0 - std::exp(-3.0), 2), 1e-3);
}

TEST(MotorQuadrotor, TorqueFreeTumbleKeepsAngularMomentumAndEnergy) {
  // Motors stopped, no gravity, a full inertia tensor (products of inertia included):
  // Euler's equations J w' = -w x J w keep the world-frame angular momentum R J w and the
  // energy w^T J w / 2 constant, while w itself wobbles (an asymmetric body about no
  // principal axis).
  MotorQuadrotorParams params;
  params.inertia_products_kg_m2 = Eigen::Vector3d(0.002, -0.001, 0.003);
  const MotorQuadrotor plant(params);
  const Eigen::Matrix3d j = params.inertia_kg_m2();
  MotorQuadrotorState s;
  s.body.body_rate_rad_s = Vec3(1.0, 2.0, 3.0);
  const auto momentum = [&] {
    return Eigen::Vector3d(s.body.attitude.eigen().toRotationMatrix() * j *
                           s.body.body_rate_rad_s.eigen());
  };
  const auto energy = [&] {
    const Eigen::Vector3d w = s.body.body_rate_rad_s.eigen();
    return 0.5 * w.dot(j * w);
  };
  const Eigen::Vector3d momentum_0 = momentum();
  const double energy_0 = energy();
  for (int i = 0; i < 2000; ++i) plant.step(s, {0.0, 0.0, 0.0, 0.0}, 0.0, 0.0, kDt);
  EXPECT_GT((s.body.body_rate_rad_s.eigen() - Eigen::Vector3d(1, 2, 3)).norm(), 0.1);
  EXPECT_LT((momentum() - momentum_0).norm(), 1e-9);
  EXPECT_NEAR(energy(), energy_0, 1e-9);
}

TEST(MotorQuadrotor, NonFiniteOrOutOfRangeOutputsAreClipped) {
  const MotorQuadrotor plant(MotorQuadrotorParams{});
  const auto w = plant.steady_rotor_speeds({std::nan(""), -0.5, 1.5, 0.25});
  EXPECT_EQ(w[0], 0.0);
  EXPECT_EQ(w[1], 0.0);
  EXPECT_EQ(w[2], 1100.0);
  EXPECT_NEAR(w[3], 550.0, 1e-9);  // 1100 sqrt(0.25)
}

// A world whose one UGV drives a circle (0.5 m/s, 0.35 rad/s): its states move the deck
// under the motor-level plant, which rests on it through the shared contact model.
class MotorQuadrotorOnDeck : public ::testing::Test {
 protected:
  MotorQuadrotorOnDeck() : world_(test::noiseless_world({test::circle(0.5, 0.35)})) {}

  SurfaceContact surfaces() const {
    return SurfaceContact(world_.state().ugvs, world_.state().ugv_count, world_.params().ugvs);
  }

  World world_;
  MotorQuadrotor plant_{MotorQuadrotorParams{}};
  MotorQuadrotorState uav_;
  ContactState contact_;
};

TEST_F(MotorQuadrotorOnDeck, RestingVehicleMovesWithTheDeckAndItsImuFeelsIt) {
  const UgvState& ugv = world_.state().ugvs[0];
  surfaces().start_resting(contact_, 0, ugv.position_m.eigen(), ugv.yaw_rad);
  surfaces().carry(contact_, uav_.body);
  UavSensorParams sensor_params;
  sensor_params.imu.specific_force_noise_m_s2 = 0.0;
  sensor_params.imu.angular_velocity_noise_rad_s = 0.0;
  sensor_params.imu.specific_force_bias_sigma_m_s2 = 0.0;
  sensor_params.imu.angular_velocity_bias_sigma_rad_s = 0.0;
  UavSensorSuite sensors(sensor_params, 1000.0, kG, 7);

  const MotorOutputs idle{0.3, 0.3, 0.3, 0.3};  // below hover (0.515): stays down
  UavImuSample last_imu;
  for (int i = 0; i < 2000; ++i) {
    world_.step(QuadrotorCommand{});
    const Eigen::Vector3d v_before = uav_.body.velocity_m_s.eigen();
    plant_.step(uav_, idle, 0.0, kG, kDt);
    surfaces().resolve(uav_.body, contact_, plant_.params().mass_kg, kG);
    const Eigen::Vector3d accel = (uav_.body.velocity_m_s.eigen() - v_before) / kDt;
    const UavSensorFrame frame =
        sensors.update(world_.state().step_index, world_.state().time_s, uav_.body, accel);
    if (frame.imu) last_imu = *frame.imu;
  }
  ASSERT_TRUE(contact_.resting);
  EXPECT_EQ(contact_.surface, 0);
  // Carried: at the deck centre, at its velocity and heading, turning at its yaw rate.
  const UgvState& moved = world_.state().ugvs[0];
  EXPECT_GT((moved.position_m.eigen() - Eigen::Vector3d(0, 0, 0.3)).norm(), 0.5);  // it drove
  EXPECT_LT((uav_.body.position_m.eigen() - moved.position_m.eigen()).norm(), 1e-12);
  EXPECT_LT((uav_.body.velocity_m_s.eigen() - moved.velocity_m_s.eigen()).norm(), 1e-12);
  EXPECT_NEAR(uav_.body.body_rate_rad_s.z, 0.35, 1e-12);
  // Its IMU feels the deck: centripetal v w = 0.175 m/s^2 to the left (a left turn), +g up,
  // and the yaw rate. (The acceleration is the velocity's change over a 1 ms step: the
  // deck's turn of 0.35 mrad in a step leaves an error of ~3e-5 m/s^2.)
  EXPECT_NEAR(last_imu.specific_force_flu_m_s2.x(), 0.0, 1e-3);
  EXPECT_NEAR(last_imu.specific_force_flu_m_s2.y(), 0.175, 1e-3);
  EXPECT_NEAR(last_imu.specific_force_flu_m_s2.z(), kG, 1e-9);
  EXPECT_NEAR(last_imu.angular_velocity_flu_rad_s.z(), 0.35, 1e-12);
}

TEST_F(MotorQuadrotorOnDeck, ThrustAboveTheWeightLiftsOffTheDeck) {
  const UgvState& ugv = world_.state().ugvs[0];
  surfaces().start_resting(contact_, 0, ugv.position_m.eigen(), ugv.yaw_rad);
  surfaces().carry(contact_, uav_.body);
  const MotorOutputs climb{0.7, 0.7, 0.7, 0.7};  // 14 N > 10.3 N once spun up
  for (int i = 0; i < 500; ++i) {
    world_.step(QuadrotorCommand{});
    plant_.step(uav_, climb, 0.0, kG, kDt);
    surfaces().resolve(uav_.body, contact_, plant_.params().mass_kg, kG);
  }
  EXPECT_FALSE(contact_.resting);
  EXPECT_GT(uav_.body.position_m.z, 0.3 + 0.1);
  EXPECT_GT(uav_.body.velocity_m_s.z, 0.5);
}

TEST(FirmwareUavParams, Px4FileStatesTheDefaultsAndArduCopterFileEveryField) {
  const std::string px4 = config_file("firmware_uav_px4.yaml");
  const std::string ardu = config_file("firmware_uav_arducopter.yaml");
  cover::test::expect_shipped_file_holds_defaults(FirmwareUavParams::load_file(px4, 1000.0), px4,
                                                  "firmware_uav");
  cover::test::expect_shipped_file_holds_every_field<FirmwareUavParams>(ardu, "firmware_uav");
  const FirmwareUavParams a = FirmwareUavParams::load_file(ardu, 1000.0);
  EXPECT_EQ(a.plant.motor.thrust_expo, 0.65);
  EXPECT_EQ(a.plant.rotors[0].spin, "ccw");
  EXPECT_EQ(a.plant.rotors[2].spin, "cw");
  EXPECT_EQ(a.sensors.imu.rate_hz, 1000.0);
  // Sensor rates against another physics rate: 250 Hz does not divide 400 Hz.
  EXPECT_THROW(FirmwareUavParams::load_file(px4, 400.0), config::ConfigError);
}

TEST(MotorQuadrotorParams, ValidationNamesTheKey) {
  const auto message = [](const MotorQuadrotorParams& p) {
    try {
      p.validate();
    } catch (const config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  MotorQuadrotorParams p;
  EXPECT_EQ(message(p), "");
  p.motor.spin_min = 0.5;
  p.motor.spin_max = 0.4;
  EXPECT_NE(message(p).find("motor_quadrotor.motor.spin_max"), std::string::npos) << message(p);
  p = MotorQuadrotorParams{};
  p.rotors[2].spin = "ccw";
  EXPECT_NE(message(p).find("counter-clockwise"), std::string::npos) << message(p);
  p = MotorQuadrotorParams{};
  p.motor.max_thrust_n = 2.0;  // 8 N < 1.05 kg * g
  EXPECT_NE(message(p).find("motor_quadrotor.motor.max_thrust_n"), std::string::npos);
  p = MotorQuadrotorParams{};
  p.inertia_products_kg_m2 = Eigen::Vector3d(0.05, 0.0, 0.0);  // |Ixy| > Ixx
  EXPECT_NE(message(p).find("inertia_products_kg_m2"), std::string::npos);
  p = MotorQuadrotorParams{};
  p.rotors[0].spin = "left";
  EXPECT_NE(message(p).find("motor_quadrotor.motor_1.spin"), std::string::npos) << message(p);
}

}  // namespace
}  // namespace cover::sim
