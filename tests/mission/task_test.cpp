#include <gtest/gtest.h>

#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/vocabulary/task.hpp"

using cover::config::ConfigError;
using cover::mission::FinalAction;
using cover::mission::load_task;
using cover::mission::Task;
using cover::mission::validate_task;

namespace {

const char* kLanding = R"(
task_id: t
processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.05], final_action: land, vmax_m_s: 1.5}
)";

// Expects `load_task(text)` to throw a ConfigError whose message contains `needle`.
void expect_error(const std::string& text, const std::string& needle, int ugv_count = 2) {
  try {
    load_task(YAML::Load(text), "task.yaml", ugv_count);
    FAIL() << "expected ConfigError containing " << needle;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Task, LoadsTheLeadsFormat) {
  const Task task = load_task(YAML::Load(kLanding), "task.yaml", 2);
  ASSERT_EQ(task.processes.size(), 1u);
  EXPECT_EQ(task.task_id, "t");
  EXPECT_EQ(task.processes[0].to_ugv, 1);
  EXPECT_EQ(task.processes[0].final_action, FinalAction::Land);
  EXPECT_DOUBLE_EQ(task.processes[0].final_point_m.z(), 0.05);
  EXPECT_DOUBLE_EQ(task.processes[0].vmax_m_s, 1.5);
  EXPECT_DOUBLE_EQ(task.processes[0].amax_m_s2, 2.0);  // default
}

TEST(Task, ShippedTasksLoad) {
  const std::string dir = cover::config::default_config_dir() + "/tasks/";
  EXPECT_EQ(cover::mission::load_task_file(dir + "scenario2.yaml", 2).processes.size(), 1u);
  EXPECT_EQ(cover::mission::load_task_file(dir + "scenario3.yaml", 2).processes.size(), 2u);
  EXPECT_EQ(cover::mission::load_task_file(dir + "scenario4.yaml", 3).processes.size(), 2u);
  EXPECT_EQ(cover::mission::load_task_file(dir + "table1.yaml", 2).processes.size(), 2u);
}

TEST(Task, RejectsUnknownUgv) {
  expect_error(kLanding, "unknown UGV 1", 1);
}

TEST(Task, RejectsEmptyProcessList) {
  expect_error("{task_id: e, processes: []}", "is empty");
}

TEST(Task, RejectsMissingProcessList) {
  expect_error("{task_id: e}", "'processes'");
}

TEST(Task, RejectsNaNPoint) {
  expect_error(R"(processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, .nan], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3]})",
               "processes[0].initial_point_m");
  // From a file the error says where: the key and its line.
  expect_error(R"(processes:
  - from_ugv: 0
    to_ugv: 1
    initial_point_m: [0, 0, 1]
    transition_point_m: [0, 0, 1]
    final_point_m: [0, .inf, 0.3]
    vmax_m_s: 1.0)",
               "processes[0].final_point_m: must be finite numbers (line 6)");
}

TEST(Task, RejectsUnknownKeyAndAction) {
  expect_error(R"(processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3], vmax_ms: 1})",
               "unknown key 'vmax_ms'");
  expect_error(R"(processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3], final_action: drop})",
               "none | land | deliver");
}

TEST(Task, RejectsBrokenChainAndEarlyLanding) {
  expect_error(R"(processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3]}
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3]})",
               "previous process's to_ugv");
  expect_error(R"(processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.05], final_action: land}
  - {from_ugv: 1, to_ugv: 0, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3]})",
               "land must be the last process");
}

TEST(Task, RejectsAbsurdSpeedLimit) {
  expect_error(R"(processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3], vmax_m_s: -1})",
               "vmax_m_s");
}

TEST(Task, RepeatsProcessesCyclically) {
  const Task two =
      cover::mission::load_task_file(cover::config::default_config_dir() + "/tasks/table1.yaml", 2);
  const Task five = cover::mission::repeat_processes(two, 5);
  ASSERT_EQ(five.processes.size(), 5u);
  EXPECT_EQ(five.processes[4].from_ugv, 0);
  EXPECT_EQ(five.processes[3].from_ugv, 1);
  EXPECT_NO_THROW(validate_task(five, 2));
}

TEST(Task, MethodPerTaskAndPerProcess) {
  const Task task = load_task(YAML::Load(R"(
task_id: m
method: intercept
processes:
  - {from_ugv: 0, to_ugv: 1, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3]}
  - {from_ugv: 1, to_ugv: 0, initial_point_m: [0, 0, 1], transition_point_m: [0, 0, 1],
     final_point_m: [0, 0, 0.3], method: no-ref-vxy}
)"),
                              "task.yaml", 2);
  EXPECT_EQ(task.processes[0].method, "intercept");   // the task's
  EXPECT_EQ(task.processes[1].method, "no-ref-vxy");  // its own
  // Without the key: the UAV's configured method.
  EXPECT_EQ(load_task(YAML::Load(kLanding), "task.yaml", 2).processes[0].method, "");
}

TEST(Task, RejectsAnUnknownMethodNamingItsLine) {
  expect_error(R"(task_id: m
processes:
  - from_ugv: 0
    to_ugv: 1
    initial_point_m: [0, 0, 1]
    transition_point_m: [0, 0, 1]
    final_point_m: [0, 0, 0.3]
    method: warp)",
               "processes[0].method: 'warp' is not one of cover | no-ref-vxy | coni-mpc | "
               "intercept (line 8)");
  expect_error("{task_id: m, method: Cover, processes: []}", "task.yaml.method: 'Cover'");
  // From the wire (no YAML): validation names the process.
  Task task = load_task(YAML::Load(kLanding), "task.yaml", 2);
  task.processes[0].method = "fast";
  EXPECT_THROW(validate_task(task, 2), ConfigError);
}

TEST(Task, NamesEachUgvOnceInTheOrderTheProcessesFlyThem) {
  Task task;
  EXPECT_TRUE(task.ugvs().empty());
  task.processes.resize(3);
  task.processes[0].from_ugv = 2;
  task.processes[0].to_ugv = 0;
  task.processes[1].from_ugv = 0;
  task.processes[1].to_ugv = 2;
  task.processes[2].from_ugv = 2;
  task.processes[2].to_ugv = 1;
  EXPECT_EQ(task.ugvs(), (std::vector<int>{2, 0, 1}));
}
