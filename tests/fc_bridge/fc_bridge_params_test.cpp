#include "cover/fc_bridge/fc_bridge_params.hpp"

#include <gtest/gtest.h>

#include "cover/config/config_error.hpp"
#include "cover/test/shipped_params.hpp"

namespace cover::fc_bridge {
namespace {

FcBridgeParams from_text(const std::string& text) {
  return FcBridgeParams::from_yaml(config::parse_yaml(text, "test"), "test");
}

// The shipped file documents every field (FcBridgeParams::fields) at its default.
TEST(FcBridgeParams, ShippedFileEqualsTheDefaults) {
  const std::string path = config::default_config_dir() + "/fc_bridge.yaml";
  test::expect_shipped_file_holds_defaults(FcBridgeParams::load_file(path), path, "fc_bridge");
  const FcBridgeParams d;
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
    const char* error;
  } cases[] = {
      {"fc_bridge:\n  hover_thrust: 0.95\n",
       "fc_bridge.hover_thrust: must be in [hover_thrust_min, hover_thrust_max]"},
      {"fc_bridge:\n  hover_thrust_min: 0.9\n",
       "fc_bridge.hover_thrust_max: must be >= hover_thrust_min"},
      {"fc_bridge:\n  hover_thrust_max: 1\n",
       "fc_bridge.hover_thrust_max: must be in [0.01, 0.99]"},
      {"fc_bridge:\n  cmd_timeout_s: 0\n",
       "fc_bridge.cmd_timeout_s: must be in [0.01, 1] s (PX4's own offboard loss is 1 s)"},
      {"fc_bridge:\n  heartbeat_timeout_s: .nan\n",
       "fc_bridge.heartbeat_timeout_s: must be in [0.5, 30] s (autopilots send HEARTBEAT at 1 Hz)"},
      {"fc_bridge:\n  command_retries: -1\n", "fc_bridge.command_retries: must be in [0, 20]"},
      {"fc_bridge:\n  state_rate_hz: 1\n", "fc_bridge.state_rate_hz: must be in [5, 100] Hz"},
      {"fc_bridge:\n  system_id: 256\n",
       "fc_bridge.system_id: must be in [0, 255] (0: the autopilot's)"},
      {"fc_bridge:\n  component_id: 0\n", "fc_bridge.component_id: must be in [1, 255]"},
  };
  for (const auto& c : cases) {
    try {
      from_text(c.yaml);
      ADD_FAILURE() << c.yaml << " was accepted";
    } catch (const config::ConfigError& e) {
      EXPECT_EQ(std::string(e.what()), c.error);
    }
  }
  EXPECT_EQ(from_text("fc_bridge:\n  auto_arm: true\n").auto_arm, true);
}

}  // namespace
}  // namespace cover::fc_bridge
