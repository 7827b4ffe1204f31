// The manager's answer to a submission, and what it names when a task id is reused.
#include "cover/task_manager/submission_answer.hpp"

#include <gtest/gtest.h>

#include "cover/task_manager/task_difference.hpp"
#include "test_support.hpp"

namespace cover::task_manager {
namespace {
using testing::make_task;

TEST(TaskDifferences, NameEachFieldThatDiffersKnownValueFirst) {
  const mission::Task known = make_task("hop");
  EXPECT_TRUE(task_differences(known, make_task("hop")).empty());
  mission::Task other = make_task("hop", 2);
  other.processes[0].to_ugv = 7;
  other.processes[0].final_point_m.z() = 0.05;
  const auto differences = task_differences(known, other);
  ASSERT_EQ(differences.size(), 3u);
  EXPECT_EQ(differences[0], "uav_id 0 -> 2");
  EXPECT_EQ(differences[1], "processes[0].final_point_m [0.0,0.0,0.3] -> [0.0,0.0,0.05]");
  EXPECT_EQ(differences[2], "processes[0].to_ugv 1 -> 7");
  mission::Task longer = known;
  longer.processes.push_back(known.processes[0]);
  EXPECT_EQ(task_differences(known, longer), std::vector<std::string>{"processes: 1 -> 2"});
  mission::Task method = known;
  method.processes[0].method = "intercept";
  EXPECT_EQ(task_differences(known, method),
            std::vector<std::string>{"processes[0].method \"\" -> \"intercept\""});
}

TaskStore::SubmitResult result(bool created, TaskState state, const mission::Task& task,
                               const std::string& reason) {
  TaskStore::SubmitResult r;
  r.created = created;
  r.record.task_id = task.task_id;
  r.record.uav_id = task.uav_id;
  r.record.task = task;
  r.record.state = state;
  r.record.reason = reason;
  r.record.accepted = state != TaskState::Rejected || !created;
  return r;
}

TEST(SubmissionAnswer, NewTasksAreQueuedOrRejectedWithTheReason) {
  const mission::Task task = make_task("hop", 1);
  const auto queued = answer_submission(task, result(true, TaskState::Queued, task, "q"));
  EXPECT_TRUE(queued.ok);
  EXPECT_EQ(queued.message, "queued for UAV 1");
  const auto rejected =
      answer_submission(task, result(true, TaskState::Rejected, task, "UGV 7 is down"));
  EXPECT_FALSE(rejected.ok);
  EXPECT_EQ(rejected.message, "rejected: UGV 7 is down");
}

TEST(SubmissionAnswer, AKnownIdWithTheSameContentIsAnsweredAsTheFirstTime) {
  const mission::Task task = make_task("hop");
  const auto repeat =
      answer_submission(task, result(false, TaskState::Running, task, "UAV 0 runs it"));
  EXPECT_TRUE(repeat.ok);
  EXPECT_EQ(repeat.message, "queued for UAV 0");
}

TEST(SubmissionAnswer, AKnownIdWithOtherContentIsRefusedNamingItsStateAndTheDifference) {
  const mission::Task known = make_task("hop");
  mission::Task other = known;
  other.processes[0].to_ugv = 7;
  const auto refused =
      answer_submission(other, result(false, TaskState::Running, known, "UAV 0 runs it"));
  EXPECT_FALSE(refused.ok);
  EXPECT_EQ(refused.message,
            "task 'hop' is already known: running (UAV 0 runs it); this submission differs in "
            "processes[0].to_ugv 1 -> 7 (submit it under another task_id)");
  mission::Task many = make_task("hop", 3);
  many.processes[0].from_ugv = 4;
  many.processes[0].to_ugv = 5;
  many.processes[0].vmax_m_s = 0.5;
  many.processes[0].amax_m_s2 = 0.5;
  const auto long_message =
      answer_submission(many, result(false, TaskState::Succeeded, known, "")).message;
  EXPECT_NE(long_message.find("already known: succeeded; this submission differs in uav_id 0 -> 3"),
            std::string::npos)
      << long_message;
  EXPECT_NE(long_message.find(" and 1 more (submit it under another task_id)"), std::string::npos)
      << long_message;
}

}  // namespace
}  // namespace cover::task_manager
