// What several configuration files hold twice or bound for each other is checked at load:
// the control period (mission.yaml's is the one), the planner's limit bounds against a
// task's, the fleet sizes. Each disagreement names both files and keys.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/uav/controller_config.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "cover/vocabulary/motion_limits.hpp"
#include "cover/vocabulary/task.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover {
namespace {

using uav::ControllerConfig;

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

bool names(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ConfigAgreement, ShippedFilesAgree) {
  const ControllerConfig config = ControllerConfig::load(config::default_config_dir());
  EXPECT_NO_THROW(config.check_agreement());
  // cover-sim's tick rate (its own file, read by the simulator's process).
  const YAML::Node sim =
      YAML::LoadFile(config::default_config_dir() + "/sim/sim_process.yaml")["sim_process"];
  ASSERT_TRUE(sim["control_rate_hz"]) << "sim_process.yaml names its control rate";
  EXPECT_NO_THROW(mission::check_control_period(
      config.mission, 1.0 / sim["control_rate_hz"].as<double>(), "sim_process.control_rate_hz"));
}

TEST(ConfigAgreement, SampcControlPeriodMustBeTheMissions) {
  ControllerConfig config = ControllerConfig::load(config::default_config_dir());
  config.sampc.control_period_s = 0.02;
  const std::string error = error_of([&] { config.validate(); });
  EXPECT_TRUE(names(error, "sampc.yaml: sampc.control_period_s (0.02 s)")) << error;
  EXPECT_TRUE(names(error, "mission.yaml: mission.control_period_s (0.01 s)")) << error;
  config.mission.control_period_s = 0.02;
  EXPECT_EQ(error_of([&] { config.validate(); }), "accepted");
}

TEST(ConfigAgreement, PlannerMustPlanEveryTasksLimits) {
  ControllerConfig config = ControllerConfig::load(config::default_config_dir());
  config.planner.max_limit_m_s = mission::kPlausibleVmax_m_s - 1.0;
  config.planner.default_vmax_m_s = 1.0;
  const std::string error = error_of([&] { config.validate(); });
  EXPECT_TRUE(names(error, "planner.yaml: planner.max_limit_m_s")) << error;
  EXPECT_TRUE(names(error, "largest vmax_m_s a task may have")) << error;

  config = ControllerConfig::load(config::default_config_dir());
  config.planner.max_limit_m_s2 = mission::kPlausibleAmax_m_s2 - 1.0;
  config.planner.default_amax_m_s2 = 1.0;
  EXPECT_TRUE(names(error_of([&] { config.validate(); }), "planner.yaml: planner.max_limit_m_s2"));
}

TEST(ConfigAgreement, HarnessRateMustBeTheControlPeriod) {
  const sim::Scenario scenario = sim::Scenario::load_file(sim::scenario_path("hover"));
  sim::ClosedLoopOptions options;
  options.control_rate_hz = 50.0;  // divides the physics rate, but is not mission.yaml's
  const std::string error = error_of([&] {
    sim::ClosedLoop(scenario, ControllerConfig::load_default(sampc::Mode::Cover), options);
  });
  EXPECT_TRUE(names(error, "closed_loop.control_rate_hz 50 Hz (0.02 s)")) << error;
  EXPECT_TRUE(names(error, "mission.yaml: mission.control_period_s")) << error;
}

TEST(ConfigAgreement, TaskLimitsAreOneDefinition) {
  const mission::TransitionProcess process;
  EXPECT_EQ(process.vmax_m_s, mission::kDefaultVmax_m_s);
  EXPECT_EQ(process.amax_m_s2, mission::kDefaultAmax_m_s2);
  mission::Task task;
  task.processes.push_back(process);
  task.processes[0].vmax_m_s = mission::kPlausibleVmax_m_s;
  EXPECT_NO_THROW(cover::mission::validate_task(task, 2));
  task.processes[0].vmax_m_s = mission::kPlausibleVmax_m_s * 1.01;
  const std::string error = error_of([&] { cover::mission::validate_task(task, 2); });
  EXPECT_TRUE(names(error, "vmax_m_s")) << error;
  EXPECT_TRUE(names(error, "(0, 20]")) << error;
}

TEST(ConfigAgreement, FleetSizesAreOneDefinition) {
  // The shared-memory world is sized by the fleet's limits, not by numbers of its own.
  EXPECT_EQ(&sim::kMaxUgvs, &fleet::kMaxUgvs);
  EXPECT_EQ(&sim::kMaxUavs, &fleet::kMaxUavs);
  EXPECT_EQ(sim::SharedWorld{}.uavs.size(), static_cast<std::size_t>(fleet::kMaxUavs));
  EXPECT_EQ(sim::SharedWorld{}.imu.size(), static_cast<std::size_t>(fleet::kMaxUgvs));
}

}  // namespace
}  // namespace cover
