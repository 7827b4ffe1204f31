#include <gtest/gtest.h>

#include <cmath>

#include "cover/mission/mission_params.hpp"
#include "cover/mission/radial_approach.hpp"

namespace cover::mission {
namespace {

using Eigen::Vector3d;

constexpr int kNodes = 20;
constexpr double kStep_s = 0.1;

sampc::HorizonReference approach(const Vector3d& p, double closing_m_s,
                                 const RadialApproachLimits& limits) {
  sampc::HorizonReference reference = sampc::HorizonReference::hold(Vector3d(9.0, 9.0, 1.5));
  fill_radial_approach(p, closing_m_s, 0.0, limits, kNodes, kStep_s, reference);
  return reference;
}

// At the frame switch the speed-up's acceleration starts at 0 and reaches amax after the
// ramp; from then on (and with no ramp) it is amax.
TEST(RadialApproach, SpeedUpRampsItsAccelerationFromTheStageStart) {
  RadialApproachLimits limits;
  limits.amax_m_s2 = 2.0;
  EXPECT_DOUBLE_EQ(speed_up_m_s(0.0, 0.25, limits), 0.5);
  limits.speed_up_ramp_s = 0.5;
  EXPECT_DOUBLE_EQ(speed_up_m_s(0.0, 0.25, limits), 2.0 * 0.25 * 0.25 / (2.0 * 0.5));
  EXPECT_DOUBLE_EQ(speed_up_m_s(0.0, 0.5, limits), 0.5);   // the ramp's mean: amax / 2
  EXPECT_DOUBLE_EQ(speed_up_m_s(0.6, 0.25, limits), 0.5);  // past the ramp
  // Across its end: 0.25 s of the ramp (0.5 - 0.125 m/s) and 0.25 s at amax (0.5 m/s).
  EXPECT_NEAR(speed_up_m_s(0.25, 0.5, limits), 0.375 + 0.5, 1e-12);
  const Vector3d p(5.0, 0.0, 1.0);
  sampc::HorizonReference early = sampc::HorizonReference::hold(Vector3d::Zero());
  sampc::HorizonReference late = early;
  fill_radial_approach(p, 0.0, 0.0, limits, kNodes, kStep_s, early);
  fill_radial_approach(p, 0.0, 5.0, limits, kNodes, kStep_s, late);
  EXPECT_GT(early.position_m[5].x(), late.position_m[5].x());  // closes later at the switch
}

TEST(RadialApproach, ClosesOnTheAxisAlongTheLineWithinTheLimits) {
  RadialApproachLimits limits;
  limits.vmax_m_s = 1.0;
  limits.amax_m_s2 = 2.0;
  limits.brake_m_s2 = 1.0;
  const Vector3d p(3.0, -4.0, 1.2);  // 5 m out
  const sampc::HorizonReference r = approach(p, 0.2, limits);
  const Eigen::Vector2d outward = p.head<2>().normalized();
  double previous_radius = 5.0;
  for (int k = 0; k <= kNodes; ++k) {
    const Eigen::Vector2d at = r.position_m[k].head<2>();
    EXPECT_NEAR(at.x() * outward.y() - at.y() * outward.x(), 0.0, 1e-12) << k;  // on the line
    EXPECT_LE(at.norm(), previous_radius + 1e-12);
    previous_radius = at.norm();
    const double speed = r.velocity_m_s[k].head<2>().norm();
    EXPECT_NEAR(speed, braking_speed_m_s(at.norm(), limits), 1e-12);  // eq. 30's v0d
    EXPECT_LE(speed, limits.vmax_m_s + 1e-12);
    EXPECT_LT(r.velocity_m_s[k].head<2>().dot(outward), 1e-12);  // toward the axis
    EXPECT_EQ(r.position_m[k].z(), 1.5);                         // heights are the plan's
  }
  // The radius shrinks from the closing speed now: 2 s = 0.4 s speeding up from 0.2 to 1 m/s
  // at amax (0.24 m), then 1.6 s at 1 m/s.
  EXPECT_NEAR(r.position_m[kNodes].head<2>().norm(), 5.0 - 0.24 - 1.6, 0.02);
}

TEST(RadialApproach, BrakesToAStopOnTheAxis) {
  RadialApproachLimits limits;
  limits.vmax_m_s = 1.5;
  limits.brake_m_s2 = 1.0;
  const sampc::HorizonReference r = approach(Vector3d(0.5, 0.0, 1.0), 1.0, limits);
  for (int k = 0; k <= kNodes; ++k) {
    const double radius = r.position_m[k].head<2>().norm();
    EXPECT_LE(r.velocity_m_s[k].head<2>().norm(), std::sqrt(2.0 * radius) + 1e-12) << k;
  }
  EXPECT_LT(r.position_m[kNodes].head<2>().norm(), 1e-3);
  EXPECT_LT(r.velocity_m_s[kNodes].head<2>().norm(), 0.05);
}

TEST(RadialApproach, MovingAwayStartsFromRestAndOnTheAxisStaysThere) {
  const RadialApproachLimits limits;
  const sampc::HorizonReference away = approach(Vector3d(2.0, 0.0, 1.0), -0.7, limits);
  // Moving away: the radius starts shrinking from rest (not from -0.7 m/s) ...
  EXPECT_NEAR(away.position_m[1].head<2>().norm(), 2.0 - 0.5 * limits.amax_m_s2 * 0.01, 2e-3);
  // ... and v0d asks for the braking curve's speed.
  EXPECT_NEAR(away.velocity_m_s[0].head<2>().norm(), braking_speed_m_s(2.0, limits), 1e-12);
  const sampc::HorizonReference on_axis = approach(Vector3d(0.0, 0.0, 1.0), 0.0, limits);
  for (int k = 0; k <= kNodes; ++k) {
    EXPECT_TRUE(on_axis.position_m[k].allFinite());
    EXPECT_EQ(on_axis.position_m[k].head<2>().norm(), 0.0);
    EXPECT_EQ(on_axis.velocity_m_s[k].head<2>().norm(), 0.0);
  }
}

TEST(MissionParams, TransitionReferenceIsParsedAndChecked) {
  const auto load = [](const std::string& text) {
    config::YamlReader reader(YAML::Load(text), "test:mission");
    return MissionParams::load(reader);
  };
  EXPECT_EQ(load("transition_reference: planned").transition_reference,
            TransitionReference::Planned);
  EXPECT_EQ(load("{}").transition_reference, TransitionReference::RadialApproach);
  EXPECT_THROW(load("transition_reference: curved"), config::ConfigError);
  EXPECT_THROW(load("approach_brake_fraction: 0"), config::ConfigError);
  EXPECT_THROW(load("approach_brake_fraction: 1.5"), config::ConfigError);
  EXPECT_DOUBLE_EQ(load("{}").final_start_acceleration_fraction, 0.3);
  EXPECT_DOUBLE_EQ(load("final_start_acceleration_fraction: 0").final_start_acceleration_fraction,
                   0.0);
  EXPECT_THROW(load("final_start_acceleration_fraction: -0.1"), config::ConfigError);
  EXPECT_THROW(load("final_start_acceleration_fraction: 1.5"), config::ConfigError);
  EXPECT_DOUBLE_EQ(load("{}").approach_speed_up_ramp_s, 0.5);
  EXPECT_DOUBLE_EQ(load("approach_speed_up_ramp_s: 0").approach_speed_up_ramp_s, 0.0);
  EXPECT_THROW(load("approach_speed_up_ramp_s: -0.1"), config::ConfigError);
  EXPECT_THROW(load("approach_speed_up_ramp_s: .nan"), config::ConfigError);
  EXPECT_THROW(load("approach_speed_up_ramp_s: 6"), config::ConfigError);
}

}  // namespace
}  // namespace cover::mission
