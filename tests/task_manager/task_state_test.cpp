#include <gtest/gtest.h>

#include <cmath>

#include "cover/task_manager/store_error.hpp"
#include "cover/task_manager/task_json.hpp"
#include "cover/task_manager/task_state.hpp"
#include "test_support.hpp"

namespace cover::task_manager {
namespace {

TEST(TaskManagerState, NamesParseBackAndFinalStatesAreTheFour) {
  const TaskState all[] = {TaskState::Queued,    TaskState::Dispatched, TaskState::Running,
                           TaskState::Succeeded, TaskState::Failed,     TaskState::Aborted,
                           TaskState::Rejected};
  const char* names[] = {"queued", "dispatched", "running", "succeeded",
                         "failed", "aborted",    "rejected"};
  for (int i = 0; i < 7; ++i) {
    EXPECT_STREQ(to_string(all[i]), names[i]);
    ASSERT_TRUE(parse_task_state(names[i]).has_value());
    EXPECT_EQ(*parse_task_state(names[i]), all[i]);
    EXPECT_EQ(is_final(all[i]), i >= 3) << names[i];
  }
  EXPECT_FALSE(parse_task_state("Queued").has_value());
  EXPECT_FALSE(parse_task_state("").has_value());
}

TEST(TaskManagerJson, EveryFieldRoundTripsIncludingNonFiniteNumbers) {
  mission::Task task = testing::make_task("json-1", 3);
  mission::TransitionProcess second = task.processes[0];
  second.from_ugv = 1;
  second.to_ugv = 2;
  second.initial_point_m = {0.1, 1.0 / 3.0, 2.5};
  second.transition_point_m = {-7.25, 1e-9, std::nan("")};
  second.final_point_m = {INFINITY, -INFINITY, 0.125};
  second.final_action = mission::FinalAction::Deliver;
  second.vmax_m_s = 2.75;
  second.amax_m_s2 = 4.5;
  second.method = "intercept";
  task.processes[0].final_action = mission::FinalAction::None;
  task.processes.push_back(second);

  const mission::Task back = task_from_json(task_to_json(task));
  EXPECT_EQ(back.task_id, "json-1");
  EXPECT_EQ(back.uav_id, 3);
  ASSERT_EQ(back.processes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& a = task.processes[i];
    const auto& b = back.processes[i];
    EXPECT_EQ(a.from_ugv, b.from_ugv);
    EXPECT_EQ(a.to_ugv, b.to_ugv);
    EXPECT_EQ(a.final_action, b.final_action);
    EXPECT_EQ(a.vmax_m_s, b.vmax_m_s);
    EXPECT_EQ(a.amax_m_s2, b.amax_m_s2);
    EXPECT_EQ(a.method, b.method);
    for (int k = 0; k < 3; ++k) {
      for (const auto& [x, y] : {std::pair{a.initial_point_m[k], b.initial_point_m[k]},
                                 std::pair{a.transition_point_m[k], b.transition_point_m[k]},
                                 std::pair{a.final_point_m[k], b.final_point_m[k]}}) {
        if (std::isnan(x)) {
          EXPECT_TRUE(std::isnan(y));
        } else {
          EXPECT_EQ(x, y);  // bit-exact: JSON doubles are written with round-trip precision
        }
      }
    }
  }
  EXPECT_NE(task_to_json(task).find("\"deliver\""), std::string::npos);
}

// Tasks stored before processes carried a method read as the UAV's own method.
TEST(TaskManagerJson, AProcessWithoutAMethodReadsAsTheUavsOwn) {
  mission::Task task = testing::make_task("old-format");
  task.processes[0].method = "coni-mpc";
  std::string json = task_to_json(task);
  const std::string key = ",\"method\":\"coni-mpc\"";
  const auto at = json.find(key);
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_EQ(task_from_json(json).processes[0].method, "coni-mpc");
  json.erase(at, key.size());
  EXPECT_EQ(task_from_json(json).processes[0].method, "");
}

TEST(TaskManagerJson, MalformedTextThrowsStoreError) {
  EXPECT_THROW(task_from_json("{"), StoreError);
  EXPECT_THROW(task_from_json("{\"task_id\": \"a\"}"), StoreError);
  EXPECT_THROW(task_from_json("{\"task_id\": \"a\", \"uav_id\": 0, \"processes\": 3}"), StoreError);
  std::string json = task_to_json(testing::make_task("a"));
  const auto at = json.find("\"land\"");
  ASSERT_NE(at, std::string::npos);
  json.replace(at, 6, "\"fly\"");
  EXPECT_THROW(task_from_json(json), StoreError);
}

}  // namespace
}  // namespace cover::task_manager
