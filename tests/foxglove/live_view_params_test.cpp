// cover-foxglove-bridge's settings (foxglove/params): the shipped file states every default,
// and a bad value names its key.
#include "cover/foxglove/live_view_params.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <utility>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/test/shipped_params.hpp"

namespace cover::foxglove {
namespace {

TEST(LiveViewParams, TheShippedFileHoldsTheDefaults) {
  const std::string path = std::string(COVER_CONFIG_DIR) + "/foxglove_bridge.yaml";
  cover::test::expect_shipped_file_holds_defaults(LiveViewParams::load_file(path), path,
                                                  "foxglove");
}

TEST(LiveViewParams, AnEmptyFileTakesTheDefaultsAndKeysOverrideThem) {
  EXPECT_EQ(LiveViewParams::from_yaml(YAML::Load("{}"), "empty.yaml").port, 8765);
  const auto p = LiveViewParams::from_yaml(
      YAML::Load("foxglove: {port: 0, uavs: 2, address: 127.0.0.1}"), "test.yaml");
  EXPECT_EQ(p.port, 0);
  EXPECT_EQ(p.uavs, 2);
  EXPECT_EQ(p.address, "127.0.0.1");
  EXPECT_EQ(p.ugvs, LiveViewParams{}.ugvs);
}

TEST(LiveViewParams, BadValuesAndUnknownKeysNameTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"foxglove: {port: 70000}", "foxglove.port"},
      {"foxglove: {uavs: 0}", "foxglove.uavs"},
      {"foxglove: {client_queue_kib: 1}", "foxglove.client_queue_kib"},
      {"foxglove: {scene_rate_hz: .nan}", "foxglove.scene_rate_hz"},
      {"foxglove: {stale_after_s: 0}", "foxglove.stale_after_s"},
      {"foxglove: {deck_size: 2}", "deck_size"},
      {"live_view: {port: 1}", "live_view"}};
  for (const auto& [yaml, key] : cases) {
    try {
      LiveViewParams::from_yaml(YAML::Load(yaml), "test.yaml");
      ADD_FAILURE() << yaml << " was accepted";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << yaml << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace cover::foxglove
