#include "cover/task_manager/flyability.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/test/shipped_params.hpp"
#include "test_support.hpp"

namespace cover::task_manager {
namespace {

constexpr double kNow_s = 1000.0;

LiveView fleet_up() {
  LiveView live;
  for (int u = 0; u < 2; ++u) {
    AgentReport report;
    report.uav_id = u;
    report.heard_s = kNow_s - 0.1;
    live.agents[u] = report;
  }
  for (int k = 0; k < 4; ++k) live.ugv_imu_heard_s[k] = kNow_s - 0.05;
  return live;
}

// G0 -> G1 -> G2 -> G0, delivering at G1 and G2, landing on G0.
mission::Task three_processes() {
  mission::Task task = testing::make_task("tour", 1);
  task.processes[0].final_action = mission::FinalAction::Deliver;
  for (const auto& [from, to] : {std::pair{1, 2}, std::pair{2, 0}}) {
    mission::TransitionProcess p = task.processes[0];
    p.from_ugv = from;
    p.to_ugv = to;
    task.processes.push_back(p);
  }
  task.processes[2].final_action = mission::FinalAction::Land;
  return task;
}

std::string why(const mission::Task& task, const LiveView& live = fleet_up()) {
  return why_not_flyable(task, live, TaskLimits{}, kNow_s).value_or("flyable");
}

TEST(TaskManagerFlyability, AFlyableTaskHasNoReason) {
  EXPECT_EQ(why(three_processes()), "flyable");
  EXPECT_EQ(why(testing::make_task("t", 0)), "flyable");
}

TEST(TaskManagerFlyability, SilentUavIsNotUp) {
  LiveView live = fleet_up();
  live.agents[1].heard_s = kNow_s - 3.2;
  EXPECT_EQ(why(three_processes(), live), "UAV 1 is not up (no heartbeat for 3.2 s)");
  live.agents.erase(1);
  EXPECT_EQ(why(three_processes(), live), "UAV 1 is not up (never heard)");
}

TEST(TaskManagerFlyability, UgvWithoutImuIsNamed) {
  mission::Task task = three_processes();
  task.processes[1].to_ugv = 3;
  task.processes[2].from_ugv = 3;
  LiveView live = fleet_up();
  live.ugv_imu_heard_s.erase(3);
  EXPECT_EQ(why(task, live), "UGV 3 is not publishing its IMU");
  live.ugv_imu_heard_s[3] = kNow_s - 2.5;
  EXPECT_EQ(why(task, live), "UGV 3 is not publishing its IMU (not heard for 2.5 s)");
  live.ugv_imu_heard_s[3] = kNow_s - 0.5;
  EXPECT_EQ(why(task, live), "flyable");
}

TEST(TaskManagerFlyability, NonFinitePointIsNamedByProcessAndAxis) {
  mission::Task task = three_processes();
  task.processes[2].final_point_m.z() = std::nan("");
  EXPECT_EQ(why(task), "process 2: final_point_m.z is NaN");
  task.processes[2].final_point_m.z() = 0.3;
  task.processes[1].initial_point_m.y() = -INFINITY;
  EXPECT_EQ(why(task), "process 1: initial_point_m.y is infinite");
}

TEST(TaskManagerFlyability, LimitsAboveTheVehiclesAreNamed) {
  mission::Task task = three_processes();
  task.processes[0].vmax_m_s = 9.0;
  EXPECT_EQ(why(task), "process 0: vmax_m_s 9 is above the vehicle's 3 m/s");
  task.processes[0].vmax_m_s = 1.0;
  task.processes[1].amax_m_s2 = 5.5;
  EXPECT_EQ(why(task), "process 1: amax_m_s2 5.5 is above the vehicle's 5 m/s^2");
}

TEST(TaskManagerFlyability, PointsOutsideTheFieldAreNamed) {
  mission::Task task = three_processes();
  task.processes[1].transition_point_m.x() = 25.0;
  EXPECT_EQ(why(task), "process 1: transition_point_m.x 25 m is beyond the +-20 m limit");
  task.processes[1].transition_point_m.x() = 0.0;
  task.processes[0].initial_point_m.z() = 12.0;
  EXPECT_EQ(why(task), "process 0: initial_point_m.z 12 m is above the 10 m limit");
  task.processes[0].initial_point_m.z() = -0.75;
  EXPECT_EQ(why(task), "process 0: initial_point_m.z -0.75 m is below the -0.5 m limit");
}

TEST(TaskManagerFlyability, TaskValidateMessageIsPassedThrough) {
  mission::Task task = three_processes();
  task.processes[2].from_ugv = 1;  // chain break: the UAV is at G2
  EXPECT_EQ(why(task),
            "task 'tour'.processes[2].from_ugv: must equal the previous process's to_ugv (the "
            "UAV is there)");
  mission::Task land_early = three_processes();
  land_early.processes[0].final_action = mission::FinalAction::Land;
  EXPECT_NE(why(land_early).find("land must be the last process"), std::string::npos);
  mission::Task empty = three_processes();
  empty.processes.clear();
  EXPECT_NE(why(empty).find("nothing to fly"), std::string::npos);
}

TEST(TaskManagerFlyability, TheTasksOwnFaultComesBeforeADownVehicle) {
  mission::Task task = three_processes();
  task.processes[2].final_point_m.z() = std::nan("");
  LiveView live = fleet_up();
  live.agents.clear();
  EXPECT_EQ(why(task, live), "process 2: final_point_m.z is NaN");
}

TEST(TaskManagerFlyability, SoundnessIgnoresTheFleet) {
  EXPECT_FALSE(why_not_sound(three_processes(), TaskLimits{}));
  mission::Task task = three_processes();
  task.processes[1].vmax_m_s = 9.0;
  EXPECT_EQ(why_not_sound(task, TaskLimits{}).value_or("sound"),
            "process 1: vmax_m_s 9 is above the vehicle's 3 m/s");
}

// What a manager that has just started waits for: a vehicle it listens to and has not heard
// yet; not one heard once (even long ago: then it is down, not undiscovered), nor an id
// beyond those it listens to.
TEST(TaskManagerFlyability, UnheardVehiclesAreOnlyThoseThatCouldStillBeHeard) {
  const mission::Task task = three_processes();  // UAV 1, UGVs 0, 1, 2
  LiveView live = fleet_up();
  EXPECT_FALSE(names_unheard(task, live, 4, 8));
  live.agents[1].heard_s = kNow_s - 60.0;
  EXPECT_FALSE(names_unheard(task, live, 4, 8));
  live.agents.erase(1);
  EXPECT_TRUE(names_unheard(task, live, 4, 8));
  EXPECT_FALSE(names_unheard(task, live, 1, 8)) << "UAV 1 is not listened to";
  live = fleet_up();
  live.ugv_imu_heard_s.erase(2);
  EXPECT_TRUE(names_unheard(task, live, 4, 8));
  EXPECT_FALSE(names_unheard(task, live, 4, 2)) << "UGV 2 is not listened to";
  mission::Task far = task;
  far.uav_id = -1;
  EXPECT_FALSE(names_unheard(far, fleet_up(), 4, 8));
}

TEST(TaskManagerFlyability, TheFirstUnheardVehicleIsNamedAsAPersonWould) {
  const mission::Task task = three_processes();  // UAV 1, UGVs 0, 1, 2
  LiveView live = fleet_up();
  EXPECT_EQ(first_unheard(task, live, 4, 8), std::nullopt);
  live.ugv_imu_heard_s.erase(2);
  EXPECT_EQ(first_unheard(task, live, 4, 8), std::optional<std::string>("UGV 2"));
  live.agents.erase(1);
  EXPECT_EQ(first_unheard(task, live, 4, 8), std::optional<std::string>("UAV 1"))
      << "the UAV first";
  EXPECT_EQ(first_unheard(task, live, 1, 8), std::optional<std::string>("UGV 2"));
}

TEST(TaskManagerLimits, ShippedFileHoldsTheDefaultsAndBadKeysAreNamed) {
  // Every field (TaskLimits::fields), shipped with its default value.
  const std::string path = config::default_config_dir() + "/task_manager.yaml";
  cover::test::expect_shipped_file_holds_defaults(TaskLimits::load_file(path), path,
                                                  "task_manager");

  const auto error_of = [](const std::string& yaml) {
    try {
      config::YamlReader reader(YAML::Load(yaml), "task_manager");
      TaskLimits::load(reader);
    } catch (const config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(error_of("heartbeat_timeout: 2").find("heartbeat_timeout"), std::string::npos);
  EXPECT_NE(error_of("dispatch_timeout_s: 0").find("task_manager.dispatch_timeout_s"),
            std::string::npos);
  EXPECT_NE(error_of("max_z_m: -1").find("task_manager.max_z_m"), std::string::npos);
  EXPECT_EQ(error_of("max_vmax_m_s: 2.5"), "accepted");
  // The vehicle's limits within what any task may have (mission/motion_limits.hpp).
  EXPECT_NE(error_of("max_vmax_m_s: 25").find("task_manager.max_vmax_m_s: must be in (0, 20]"),
            std::string::npos)
      << error_of("max_vmax_m_s: 25");
  EXPECT_NE(error_of("restart_grace_s: .nan").find("task_manager.restart_grace_s"),
            std::string::npos);
  EXPECT_NE(error_of("max_amax_m_s2: 31").find("task_manager.max_amax_m_s2"), std::string::npos);
}

}  // namespace
}  // namespace cover::task_manager
