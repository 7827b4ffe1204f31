#include <gtest/gtest.h>

#include <string>

#include "cover/sim/world.hpp"

namespace cover::sim {
namespace {

WorldParams load_text(const std::string& yaml) {
  cover::config::YamlReader reader(YAML::Load(yaml), "test.yaml");
  return WorldParams::load(reader);
}

std::string error_of(const std::string& yaml) {
  try {
    load_text(yaml);
  } catch (const cover::config::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(WorldParams, DefaultFileLoadsAndBuildsAWorld) {
  const WorldParams params = WorldParams::load_default();
  ASSERT_EQ(params.ugvs.size(), 2u);
  EXPECT_EQ(params.ugvs[0].pattern.kind, MotionPatternKind::Circle);
  EXPECT_DOUBLE_EQ(params.ugvs[0].pattern.speed_m_s, 0.5);
  EXPECT_DOUBLE_EQ(params.uav.mass_true_kg, 1.05);
  World world(params);
  EXPECT_EQ(world.ugv_count(), 2);
  EXPECT_DOUBLE_EQ(world.physics_dt_s(), 0.001);
}

TEST(WorldParams, EveryShippedWorldLoads) {
  for (const char* name : {"world_default", "world_figure_eight", "world_star", "world_s_curve",
                           "world_lines", "world_three_circles"}) {
    SCOPED_TRACE(name);
    const std::string path = cover::config::default_config_dir() + "/sim/" + name + ".yaml";
    EXPECT_NO_THROW(World(WorldParams::load_file(path)));
  }
}

// One source of truth: the harness filters with the agent's configuration.
TEST(WorldParams, ImuFilterComesFromTheAgentConfiguration) {
  const auto agent_filter = cover::ugv::ImuFilterParams::load_default();
  const WorldParams params = WorldParams::load_default();
  EXPECT_EQ(params.imu_filter.specific_force_cutoff_hz, agent_filter.specific_force_cutoff_hz);
  EXPECT_EQ(params.imu_filter.angular_velocity_cutoff_hz, agent_filter.angular_velocity_cutoff_hz);
  EXPECT_EQ(params.imu_filter.angular_acceleration_cutoff_hz,
            agent_filter.angular_acceleration_cutoff_hz);
  EXPECT_EQ(params.imu_filter.max_sample_gap_s, agent_filter.max_sample_gap_s);
  EXPECT_EQ(params.imu_filter.max_specific_force_m_s2, agent_filter.max_specific_force_m_s2);
  EXPECT_EQ(params.imu_filter.max_angular_velocity_rad_s, agent_filter.max_angular_velocity_rad_s);
  const std::string moved =
      error_of("imu_filter: {max_sample_gap_s: 0.2}\nugvs: [{pattern: {kind: stationary}}]");
  EXPECT_NE(moved.find("ugv_agent.yaml"), std::string::npos) << moved;
}

TEST(WorldParams, MinimalYamlUsesDefaults) {
  const WorldParams params = load_text("ugvs: [{pattern: {kind: stationary}}]");
  EXPECT_EQ(params.ugvs.size(), 1u);
  EXPECT_DOUBLE_EQ(params.physics_rate_hz, 1000.0);
}

TEST(WorldParams, ErrorsNameTheBadKey) {
  EXPECT_NE(error_of("ugvs: [{pattern: {kind: circle, speed_ms: 1}}]").find("speed_ms"),
            std::string::npos);
  EXPECT_NE(error_of("ugvs: [{pattern: {kind: zigzag}}]").find("kind"), std::string::npos);
  EXPECT_NE(error_of("ugvs: [{pattern: {kind: circle, yaw_rate_rad_s: 0}}]").find("yaw_rate_rad_s"),
            std::string::npos);
  EXPECT_NE(error_of("world: {physics_rate_hz: 1000}\nimu: {rate_hz: 300}\n"
                     "ugvs: [{pattern: {kind: stationary}}]")
                .find("imu.rate_hz"),
            std::string::npos);
  EXPECT_NE(error_of("uav: {plant: {mass_true_kg: -1}}\nugvs: [{pattern: {kind: stationary}}]")
                .find("mass_true_kg"),
            std::string::npos);
  EXPECT_NE(error_of("uav: {initial: {start_on_ugv: 3}}\nugvs: [{pattern: {kind: stationary}}]")
                .find("start_on_ugv"),
            std::string::npos);
  EXPECT_NE(error_of("world: {seed: 1}").find("ugvs"), std::string::npos);
}

}  // namespace
}  // namespace cover::sim
