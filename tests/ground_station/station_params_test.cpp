// cover-ground-station's settings (ground_station/params): the shipped file states every
// default, and a bad value names its key.
#include "cover/ground_station/station_params.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <utility>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/test/shipped_params.hpp"

namespace cover::ground_station {
namespace {

TEST(StationParams, TheShippedFileHoldsTheDefaults) {
  const std::string path = std::string(COVER_CONFIG_DIR) + "/ground_station.yaml";
  cover::test::expect_shipped_file_holds_defaults(StationParams::load_file(path), path,
                                                  "ground_station");
}

TEST(StationParams, AnEmptyFileTakesTheDefaultsAndKeysOverrideThem) {
  EXPECT_EQ(StationParams::from_yaml(YAML::Load("{}"), "empty.yaml").port, 8080);
  const auto p = StationParams::from_yaml(
      YAML::Load("ground_station: {port: 0, push_coalesce_ms: 0, bind: 127.0.0.2}"), "t.yaml");
  EXPECT_EQ(p.port, 0);
  EXPECT_EQ(p.push_coalesce_ms, 0.0);
  EXPECT_EQ(p.bind, "127.0.0.2");
  EXPECT_EQ(p.state_rate_hz, StationParams{}.state_rate_hz);
}

TEST(StationParams, BadValuesAndUnknownKeysNameTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"ground_station: {port: 70000}", "ground_station.port"},
      {"ground_station: {state_rate_hz: 0.5}", "ground_station.state_rate_hz"},
      {"ground_station: {push_coalesce_ms: -1}", "ground_station.push_coalesce_ms"},
      {"ground_station: {push_coalesce_ms: .nan}", "ground_station.push_coalesce_ms"},
      {"ground_station: {client_queue_kib: 1}", "ground_station.client_queue_kib"},
      {"ground_station: {manager_query_period_s: 0}", "ground_station.manager_query_period_s"},
      {"ground_station: {uavs: 0}", "ground_station.uavs"},
      {"ground_station: {state_rate: 5}", "state_rate"},
      {"station: {port: 1}", "station"}};
  for (const auto& [yaml, key] : cases) {
    try {
      StationParams::from_yaml(YAML::Load(yaml), "test.yaml");
      ADD_FAILURE() << yaml << " was accepted";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << yaml << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace cover::ground_station
