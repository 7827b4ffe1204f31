#include "cover/fc_bridge/fc_bridge_params.hpp"

#include <gtest/gtest.h>

#include "cover/config/config_error.hpp"

namespace cover::fc_bridge {
namespace {

FcBridgeParams from_text(const std::string& text) {
  return FcBridgeParams::from_yaml(config::parse_yaml(text, "test"), "test");
}

// The shipped file documents the defaults: loading it must give the struct's defaults.
TEST(FcBridgeParams, ShippedFileEqualsTheDefaults) {
  const FcBridgeParams shipped =
      FcBridgeParams::load_file(config::default_config_dir() + "/fc_bridge.yaml");
  const FcBridgeParams d;
  EXPECT_EQ(shipped.hover_thrust, d.hover_thrust);
  EXPECT_EQ(shipped.hover_thrust_min, d.hover_thrust_min);
  EXPECT_EQ(shipped.hover_thrust_max, d.hover_thrust_max);
  EXPECT_EQ(shipped.hover_thrust_initial_std, d.hover_thrust_initial_std);
  EXPECT_EQ(shipped.hover_thrust_noise_per_sqrt_s, d.hover_thrust_noise_per_sqrt_s);
  EXPECT_EQ(shipped.accel_noise_m_s2, d.accel_noise_m_s2);
  EXPECT_EQ(shipped.estimator_min_thrust, d.estimator_min_thrust);
  EXPECT_EQ(shipped.cmd_timeout_s, d.cmd_timeout_s);
  EXPECT_EQ(shipped.heartbeat_timeout_s, d.heartbeat_timeout_s);
  EXPECT_EQ(shipped.ack_timeout_s, d.ack_timeout_s);
  EXPECT_EQ(shipped.command_retries, d.command_retries);
  EXPECT_EQ(shipped.offboard_stream_s, d.offboard_stream_s);
  EXPECT_EQ(shipped.state_rate_hz, d.state_rate_hz);
  EXPECT_EQ(shipped.system_id, d.system_id);
  EXPECT_EQ(shipped.component_id, d.component_id);
  EXPECT_EQ(shipped.auto_arm, d.auto_arm);
  EXPECT_EQ(shipped.gravity_m_s2, d.gravity_m_s2);
  EXPECT_DOUBLE_EQ(d.hover_thrust, 0.4905);
  EXPECT_FALSE(d.auto_arm);
  EXPECT_EQ(d.cmd_timeout_s, 0.1);
  EXPECT_EQ(d.heartbeat_timeout_s, 1.5);
}

TEST(FcBridgeParams, UnknownKeysAreRejectedByName) {
  try {
    from_text("fc_bridge:\n  cmd_timeout: 0.2\n");
    FAIL() << "a misspelt key was accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("cmd_timeout"), std::string::npos) << e.what();
  }
}

TEST(FcBridgeParams, BadValuesNameTheKey) {
  const struct {
    const char* yaml;
    const char* key;
  } cases[] = {
      {"fc_bridge:\n  hover_thrust: 0.95\n", "fc_bridge.hover_thrust"},
      {"fc_bridge:\n  hover_thrust_min: 0.9\n", "fc_bridge.hover_thrust_max"},
      {"fc_bridge:\n  cmd_timeout_s: 0\n", "fc_bridge.cmd_timeout_s"},
      {"fc_bridge:\n  heartbeat_timeout_s: .nan\n", "fc_bridge.heartbeat_timeout_s"},
      {"fc_bridge:\n  command_retries: -1\n", "fc_bridge.command_retries"},
      {"fc_bridge:\n  state_rate_hz: 1\n", "fc_bridge.state_rate_hz"},
      {"fc_bridge:\n  system_id: 256\n", "fc_bridge.system_id"},
      {"fc_bridge:\n  component_id: 0\n", "fc_bridge.component_id"},
  };
  for (const auto& c : cases) {
    try {
      from_text(c.yaml);
      ADD_FAILURE() << c.yaml << " was accepted";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(c.key), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(from_text("fc_bridge:\n  auto_arm: true\n").auto_arm, true);
}

}  // namespace
}  // namespace cover::fc_bridge
