#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "cover/sim/world.hpp"
#include "cover/test/shipped_params.hpp"

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
  EXPECT_NE(error_of("ugvs: [{pattern: {kind: zigzag}}]")
                .find("test.yaml.ugvs[0].pattern.kind: 'zigzag' is not one of stationary, circle, "
                      "figure_eight, star, s_curve, back_and_forth"),
            std::string::npos);
  EXPECT_NE(error_of("ugvs: [{pattern: {origin_m: [1, 2]}}]")
                .find("test.yaml.ugvs[0].pattern.kind: missing required key"),
            std::string::npos);
  EXPECT_EQ(error_of("ugvs: [{pattern: {kind: circle, yaw_rate_rad_s: 0}}]"),
            "test.yaml.ugvs[0].pattern.yaw_rate_rad_s: must be non-zero on a circle, |w| >= 0.001");
  EXPECT_EQ(error_of("ugvs: [{pattern: {kind: circle, yaw_rate_rad_s: 6}}]"),
            "test.yaml.ugvs[0].pattern.yaw_rate_rad_s: must be in [-5, 5] rad/s");
  // A pattern's bounds hold for the keys its kind does not use, too.
  EXPECT_EQ(error_of("ugvs: [{pattern: {kind: stationary, star_depth: 1.5}}]"),
            "test.yaml.ugvs[0].pattern.star_depth: must be in (0, 0.9]");
  EXPECT_EQ(error_of("ugvs: [{pattern: {kind: figure_eight, half_width_m: 0}}]"),
            "test.yaml.ugvs[0].pattern.half_width_m: must be > 0 on a figure_eight");
  EXPECT_EQ(error_of("ugvs: [{name: '', pattern: {kind: stationary}}]"),
            "test.yaml.ugvs[0].name: must not be empty");
  EXPECT_EQ(error_of("ugvs: [{deck_half_width_m: 0, pattern: {kind: stationary}}]"),
            "test.yaml.ugvs[0].deck_half_width_m: must be in (0, 5] m");
  EXPECT_EQ(error_of("world: {physics_rate_hz: 1000}\nimu: {rate_hz: 300}\n"
                     "ugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.imu.rate_hz: must divide physics_rate_hz (1000.000000)");
  EXPECT_EQ(error_of("world: {gravity_m_s2: 30}\nugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.world.gravity_m_s2: must be in (0, 30) m/s^2");
  EXPECT_EQ(error_of("uav: {plant: {mass_true_kg: -1}}\nugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.uav.plant.mass_true_kg: must be in [0.01, 100] kg");
  EXPECT_EQ(error_of("uav: {plant: {drag_coefficients_1_s: [0.3, 11, 0.1]}}\n"
                     "ugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.uav.plant.drag_coefficients_1_s: each must be in [0, 10] 1/s");
  EXPECT_EQ(error_of("uav: {plant: {min_thrust_m_s2: 20}}\nugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.uav.plant.max_thrust_m_s2: must exceed min_thrust_m_s2");
  EXPECT_EQ(error_of("uav: {initial: {start_on_ugv: 3}}\nugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.uav.initial.start_on_ugv: must be -1 or the index of a listed UGV");
  EXPECT_EQ(error_of("uav: {initial: {start_on_ugv: -2}}\nugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.uav.initial.start_on_ugv: must be >= -1");
  EXPECT_EQ(error_of("uav: {initial: {position_m: [0, 0, -1]}}\n"
                     "ugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.uav.initial.position_m: must have z >= 0");
  EXPECT_EQ(error_of("payload: {mass_kg: 1.05}\nugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.payload.mass_kg: must be below uav.plant.mass_true_kg");
  EXPECT_EQ(error_of("relative_sensor: {dropout_probability: 1.5}\n"
                     "ugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.relative_sensor.dropout_probability: must be in [0, 1]");
  EXPECT_EQ(error_of("odometry: {scale_error_sigma: 0.3}\nugvs: [{pattern: {kind: stationary}}]"),
            "test.yaml.odometry.scale_error_sigma: must be in [0, 0.2]");
  EXPECT_NE(error_of("imu: {rate: 200}\nugvs: [{pattern: {kind: stationary}}]")
                .find("test.yaml.imu: unknown key 'rate'"),
            std::string::npos);
  EXPECT_NE(error_of("world: {seed: 1}").find("ugvs"), std::string::npos);
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every field of WorldParams::fields (its sections' included) is written in the default
// world at its default: the file documents them all.
TEST(WorldParams, DefaultFileWritesEveryFieldAtItsDefault) {
  const std::string path = cover::config::default_config_dir() + "/sim/world_default.yaml";
  const YAML::Node root = YAML::LoadFile(path);
  for (const std::string& key : cover::config::field_keys<WorldParams>()) {
    EXPECT_TRUE(cover::test::node_at(root, key).IsDefined())
        << path << ": " << key << " is a field but the file does not write it";
  }
  EXPECT_EQ(cover::config::field_values(WorldParams::load_default()),
            cover::config::field_values(WorldParams{}));
}

// Its first UGV writes every UgvParams field at its default, but its name and pattern; each
// pattern key is explained in the comment above the list (the patterns use a few each).
TEST(WorldParams, DefaultFileDocumentsEveryUgvAndPatternField) {
  const std::string path = cover::config::default_config_dir() + "/sim/world_default.yaml";
  const std::string text = file_text(path);
  const YAML::Node first = YAML::LoadFile(path)["ugvs"][0];
  for (const std::string& key : cover::config::field_keys<UgvParams>()) {
    const std::string pattern = "pattern.";
    if (key.compare(0, pattern.size(), pattern) == 0) {
      const std::string name = key.substr(pattern.size());
      EXPECT_NE(text.find("#   " + name + " "), std::string::npos)
          << path << ": pattern key " << name << " is not explained";
    } else {
      EXPECT_TRUE(first[key]) << path << ": ugvs[0] does not write " << key;
    }
  }
  UgvParams shipped = WorldParams::load_default().ugvs[0];
  shipped.pattern = UgvMotionPatternParams{};
  EXPECT_EQ(cover::config::field_values(shipped), cover::config::field_values(UgvParams{}));
}

}  // namespace
}  // namespace cover::sim
