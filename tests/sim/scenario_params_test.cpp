// config/scenarios: the scenario's own fields (Scenario::fields) beside its world and task.
#include <gtest/gtest.h>

#include <string>

#include "cover/config/config_error.hpp"
#include "cover/config/param_fields.hpp"
#include "cover/sim/scenario.hpp"

namespace cover::sim {
namespace {

// The shipped scenarios load; Scenario 2 writes each of the scenario's own fields.
TEST(Scenario, ShippedScenariosLoadAndScenario2WritesEachField) {
  for (const char* name :
       {"scenario1", "scenario1_lines", "scenario1_lines_short", "scenario2", "scenario3",
        "scenario4", "table1", "hover", "two_uavs", "fleet_two_uavs"}) {
    SCOPED_TRACE(name);
    EXPECT_NO_THROW(Scenario::load_file(scenario_path(name)));
  }
  const YAML::Node scenario2 = YAML::LoadFile(scenario_path("scenario2"));
  for (const std::string& key : cover::config::field_keys<Scenario>()) {
    EXPECT_TRUE(scenario2[key]) << "scenario2.yaml does not write " << key;
  }
  const auto error = [](const std::string& yaml) {
    try {
      Scenario::from_yaml(YAML::Load(yaml), scenario_path("test"));
    } catch (const cover::config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string world =
      "sim: {ugvs: [{pattern: {kind: stationary}}, "
      "{pattern: {kind: stationary}}]}\ntask_file: ../tasks/scenario2.yaml\n";
  EXPECT_EQ(error(world + "name: s\nmax_duration_s: 0"),
            "scenario 's'.max_duration_s: must be in (0, 3600] s");
  EXPECT_EQ(error(world + "name: s\nsettle_time_s: 61"),
            "scenario 's'.settle_time_s: must be in [0, 60] s");
  EXPECT_EQ(error(world + "name: s\nextra_uavs: [{task_file: ../tasks/two_uavs_uav1.yaml, "
                          "start_on_ugv: -2}]"),
            "scenario 's'.extra_uavs[0].start_on_ugv: must be >= -1");
  EXPECT_NE(error(world + "extra_uavs: [{task_file: ../tasks/two_uavs_uav1.yaml, payload: true}]")
                .find("extra_uavs[0]: unknown key 'payload'"),
            std::string::npos);
  EXPECT_NE(error(world + "max_duration: 10").find("unknown key 'max_duration'"),
            std::string::npos);
}

}  // namespace
}  // namespace cover::sim
