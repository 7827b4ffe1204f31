#include "cover/task_manager/dispatcher.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "test_support.hpp"

namespace cover::task_manager {
namespace {
using AgentTask = AgentReport::AgentTask;
using testing::make_task;

// A store on a real file, a dispatcher on it, and the fleet as the process would see it:
// UGVs 0 and 1 publishing, UAV agents reporting what the test says.
class DispatcherTest : public ::testing::Test {
 protected:
  DispatcherTest() { restart(); }

  // A new manager process on the same file.
  void restart() {
    dispatcher_.reset();
    store_ = std::make_unique<TaskStore>(dir_.file("tasks.db"));
    dispatcher_ = std::make_unique<Dispatcher>(*store_, TaskLimits{});
  }

  void hear(int uav, double now_s, const std::string& task_id = "",
            AgentTask state = AgentTask::None, const std::string& message = "") {
    AgentReport report;
    report.uav_id = uav;
    report.heard_s = now_s;
    report.task_id = task_id;
    report.task_state = state;
    report.message = message;
    live_.agents[uav] = report;
    for (int k = 0; k < 2; ++k) live_.ugv_imu_heard_s[k] = now_s;
  }
  // Heartbeat at now_s, task report unchanged.
  void hear_again(int uav, double now_s) {
    live_.agents[uav].heard_s = now_s;
    for (int k = 0; k < 2; ++k) live_.ugv_imu_heard_s[k] = now_s;
  }

  TaskStore::SubmitResult submit(const std::string& id, int uav, double now_s) {
    return dispatcher_->submit(make_task(id, uav), "ops", "req-" + id, live_, now_s);
  }
  Actions step(double now_s) { return dispatcher_->step(live_, now_s); }
  TaskState state(const std::string& id) { return store_->find(id).value().state; }
  std::string reason(const std::string& id) { return store_->find(id).value().reason; }

  testing::TempDir dir_;
  std::unique_ptr<TaskStore> store_;
  std::unique_ptr<Dispatcher> dispatcher_;
  LiveView live_;
};

TEST_F(DispatcherTest, FullLifecycleFromTheAgentsReports) {
  hear(0, 10.0);
  const auto submitted = submit("t1", 0, 10.0);
  ASSERT_TRUE(submitted.created);
  EXPECT_EQ(submitted.record.state, TaskState::Queued);

  const Actions first = step(10.1);
  ASSERT_EQ(first.dispatch.size(), 1u);
  EXPECT_EQ(first.dispatch[0].uav_id, 0);
  EXPECT_EQ(first.dispatch[0].record.task_id, "t1");
  EXPECT_EQ(first.dispatch[0].record.state, TaskState::Dispatched);
  EXPECT_EQ(first.dispatch[0].record.task.processes.size(), 1u);
  EXPECT_EQ(state("t1"), TaskState::Dispatched);
  EXPECT_TRUE(step(10.2).dispatch.empty()) << "dispatched twice";

  hear(0, 10.3, "t1", AgentTask::Pending);
  step(10.3);
  EXPECT_EQ(state("t1"), TaskState::Running);
  hear(0, 15.0, "t1", AgentTask::Running);
  EXPECT_TRUE(step(15.0).dispatch.empty());
  EXPECT_EQ(state("t1"), TaskState::Running);
  hear(0, 20.0, "t1", AgentTask::Succeeded, "landed on UGV 1");
  step(20.0);
  EXPECT_EQ(state("t1"), TaskState::Succeeded);
  EXPECT_EQ(reason("t1"), "landed on UGV 1");

  const auto history = store_->history("t1");
  ASSERT_EQ(history.size(), 4u);
  EXPECT_EQ(history[1].to, TaskState::Dispatched);
  EXPECT_EQ(history[2].to, TaskState::Running);
  EXPECT_EQ(history[3].to, TaskState::Succeeded);
  EXPECT_EQ(history[3].time_s, 20.0);
}

// Where a flight-controller bridge reports the UAV's autopilot, a task is dispatched only
// while the autopilot flies COVER's setpoints; until then it stays queued, saying why.
TEST_F(DispatcherTest, WithABridgeATaskWaitsForTheAutopilotSayingWhy) {
  hear(0, 10.0);
  live_.autopilots[0] = {10.0, "autopilot disarmed"};
  submit("t1", 0, 10.0);
  Actions actions = step(10.0);
  EXPECT_TRUE(actions.dispatch.empty());
  EXPECT_EQ(state("t1"), TaskState::Queued);
  EXPECT_EQ(reason("t1"), "waiting for UAV 0: autopilot disarmed");
  ASSERT_EQ(actions.waiting.size(), 1u);
  EXPECT_EQ(actions.waiting[0].task_id, "t1");
  EXPECT_EQ(actions.waiting[0].reason, "waiting for UAV 0: autopilot disarmed");

  hear_again(0, 10.1);
  live_.autopilots[0].heard_s = 10.1;
  actions = step(10.1);
  EXPECT_TRUE(actions.dispatch.empty());
  EXPECT_TRUE(actions.waiting.empty()) << "the same reason is not recorded again";

  live_.autopilots[0].not_ready = "autopilot not in its offboard mode (mode POSCTL)";
  EXPECT_EQ(step(10.1).waiting.size(), 1u);
  EXPECT_EQ(reason("t1"), "waiting for UAV 0: autopilot not in its offboard mode (mode POSCTL)");

  // A bridge gone silent: its autopilot's state is unknown, nothing is dispatched.
  hear_again(0, 12.0);
  step(12.0);
  EXPECT_EQ(state("t1"), TaskState::Queued);
  EXPECT_EQ(reason("t1"), "waiting for UAV 0: its flight-controller bridge not heard for 1.9 s");

  // Armed, OFFBOARD, link up: dispatched at once.
  hear_again(0, 12.1);
  live_.autopilots[0] = {12.1, ""};
  actions = step(12.1);
  ASSERT_EQ(actions.dispatch.size(), 1u);
  EXPECT_EQ(state("t1"), TaskState::Dispatched);
  EXPECT_EQ(reason("t1"), "sent to UAV 0");
  const auto history = store_->history("t1");
  ASSERT_EQ(history.size(), 5u);  // submitted, three reasons to wait, dispatched
  EXPECT_EQ(history[1].reason, "waiting for UAV 0: autopilot disarmed");
  EXPECT_EQ(history[4].to, TaskState::Dispatched);
}

// The simulator's direct path has no bridge: nothing waits for an autopilot, and a bridge
// on one UAV holds back only that UAV's queue.
TEST_F(DispatcherTest, WithoutABridgeNothingWaitsForAnAutopilot) {
  hear(0, 10.0);
  hear(1, 10.0);
  live_.autopilots[1] = {10.0, "flight-controller link lost (no autopilot HEARTBEAT)"};
  submit("direct", 0, 10.0);
  submit("bridged", 1, 10.0);
  const Actions actions = step(10.0);
  ASSERT_EQ(actions.dispatch.size(), 1u);
  EXPECT_EQ(actions.dispatch[0].record.task_id, "direct");
  EXPECT_EQ(state("bridged"), TaskState::Queued);
  EXPECT_EQ(reason("bridged"),
            "waiting for UAV 1: flight-controller link lost (no autopilot HEARTBEAT)");
}

// Issue 31: a submission rejected at once holds no id; an accepted task holds it for good.
TEST_F(DispatcherTest, ARejectedSubmissionHoldsNoIdAndAnAcceptedTaskHoldsItsId) {
  const auto rejected = submit("t1", 0, 10.0);  // UAV 0 never heard
  EXPECT_TRUE(rejected.created);
  EXPECT_EQ(rejected.record.state, TaskState::Rejected);
  EXPECT_FALSE(rejected.record.accepted);
  EXPECT_EQ(rejected.record.reason, "UAV 0 is not up (never heard)");
  const auto rejected_again = submit("t1", 0, 10.5);  // still not heard: judged anew
  EXPECT_TRUE(rejected_again.created);
  EXPECT_TRUE(rejected_again.replaced_rejected);
  EXPECT_EQ(rejected_again.record.state, TaskState::Rejected);
  hear(0, 11.0);
  const auto accepted = submit("t1", 0, 11.0);
  EXPECT_TRUE(accepted.created);
  EXPECT_TRUE(accepted.replaced_rejected);
  EXPECT_EQ(accepted.record.state, TaskState::Queued);
  EXPECT_TRUE(accepted.record.accepted);
  EXPECT_EQ(accepted.record.reason, "queued for UAV 0");
  EXPECT_EQ(store_->replaced_rejections("t1").size(), 2u);
  const Actions actions = step(11.0);
  ASSERT_EQ(actions.dispatch.size(), 1u);
  EXPECT_EQ(actions.dispatch[0].record.task_id, "t1");
  const auto repeat = submit("t1", 0, 12.0);
  EXPECT_FALSE(repeat.created) << "an accepted task holds its id";
  EXPECT_EQ(repeat.record.state, TaskState::Dispatched);
  EXPECT_EQ(submit("t2", 0, 12.0).record.state, TaskState::Queued);
  EXPECT_FALSE(submit("t2", 0, 12.0).created);
}

TEST_F(DispatcherTest, TwoUavsAreServedAtOnceEachFromItsQueueInOrder) {
  hear(0, 1.0);
  hear(1, 1.0);
  for (const char* id : {"a0", "b0", "a1", "b1", "a2"}) submit(id, id[0] == 'a' ? 0 : 1, 1.0);
  const std::vector<std::string> a = {"a0", "a1", "a2"}, b = {"b0", "b1"};
  std::vector<std::string> flown_a, flown_b;
  double t = 1.0;
  for (int round = 0; round < 3; ++round) {
    t += 1.0;
    const Actions actions = step(t);
    for (const Dispatch& d : actions.dispatch) {
      (d.uav_id == 0 ? flown_a : flown_b).push_back(d.record.task_id);
    }
    if (round < 2) {
      EXPECT_EQ(actions.dispatch.size(), 2u) << "round " << round << ": both UAVs at once";
    }
    // Both agents take and finish what they were sent.
    for (const Dispatch& d : actions.dispatch)
      hear(d.uav_id, t, d.record.task_id, AgentTask::Running);
    step(t + 0.1);
    for (const Dispatch& d : actions.dispatch) {
      hear(d.uav_id, t + 0.5, d.record.task_id, AgentTask::Succeeded);
    }
    hear_again(0, t + 0.5);
    hear_again(1, t + 0.5);
    t += 0.5;
  }
  EXPECT_EQ(flown_a, a);
  EXPECT_EQ(flown_b, b);
  for (const auto& id : {"a0", "a1", "b0", "b1"}) EXPECT_EQ(state(id), TaskState::Succeeded) << id;
}

TEST_F(DispatcherTest, AbortOfAQueuedTaskRemovesItFromItsQueue) {
  hear(0, 1.0, "other", AgentTask::Running);  // busy: nothing is dispatched
  submit("q1", 0, 1.0);
  submit("q2", 0, 1.0);
  const auto result = dispatcher_->abort("q1", "operator changed plan", 1.5);
  EXPECT_TRUE(result.ok);
  EXPECT_FALSE(result.send.has_value());
  EXPECT_EQ(state("q1"), TaskState::Aborted);
  EXPECT_EQ(reason("q1"), "operator changed plan");
  hear(0, 2.0);
  const Actions actions = step(2.0);
  ASSERT_EQ(actions.dispatch.size(), 1u);
  EXPECT_EQ(actions.dispatch[0].record.task_id, "q2");
  EXPECT_TRUE(actions.abort.empty());

  const auto again = dispatcher_->abort("q1", "twice", 2.1);
  EXPECT_FALSE(again.ok);
  EXPECT_EQ(again.message, "task 'q1' is already aborted");
  const auto unknown = dispatcher_->abort("nope", "x", 2.1);
  EXPECT_FALSE(unknown.ok);
  EXPECT_EQ(unknown.message, "no task 'nope'");
}

TEST_F(DispatcherTest, AbortOfARunningTaskIsResentUntilTheAgentReportsCancelled) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  submit("t2", 0, 1.0);
  step(1.0);
  hear(0, 1.1, "t1", AgentTask::Running);
  step(1.1);
  ASSERT_EQ(state("t1"), TaskState::Running);

  const auto result = dispatcher_->abort("t1", "operator", 2.0);
  EXPECT_TRUE(result.ok);
  ASSERT_TRUE(result.send.has_value());
  EXPECT_EQ(result.send->uav_id, 0);
  EXPECT_EQ(result.send->task_id, "t1");
  EXPECT_EQ(result.send->reason, "operator");
  EXPECT_EQ(state("t1"), TaskState::Running) << "aborted before the agent stopped";

  // The first abort is lost: the agent keeps flying, so the manager keeps sending.
  for (int i = 1; i <= 3; ++i) {
    hear(0, 2.0 + 0.1 * i, "t1", AgentTask::Running);
    const Actions actions = step(2.0 + 0.1 * i);
    ASSERT_EQ(actions.abort.size(), 1u) << "step " << i;
    EXPECT_EQ(actions.abort[0].task_id, "t1");
    EXPECT_TRUE(actions.dispatch.empty());
  }
  hear(0, 2.5, "t1", AgentTask::Cancelled, "aborted: operator");
  const Actions done = step(2.5);
  EXPECT_TRUE(done.abort.empty());
  EXPECT_EQ(state("t1"), TaskState::Aborted);
  EXPECT_EQ(reason("t1"), "aborted: operator");
  ASSERT_EQ(done.dispatch.size(), 1u);  // the agent is idle again: the queue moves on
  EXPECT_EQ(done.dispatch[0].record.task_id, "t2");
  EXPECT_TRUE(step(2.6).abort.empty());
}

TEST_F(DispatcherTest, ASilentAgentFailsItsRunningTask) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  step(1.0);
  hear(0, 1.5, "t1", AgentTask::Running);
  step(1.5);
  step(2.5);  // 1.0 s of silence: not yet
  EXPECT_EQ(state("t1"), TaskState::Running);
  step(2.6);
  EXPECT_EQ(state("t1"), TaskState::Failed);
  EXPECT_EQ(reason("t1"), "UAV 0 went silent (no heartbeat for 1.1 s)");
}

TEST_F(DispatcherTest, FailsafeEntriesAndExitsAreInTheTasksHistoryWithTheirCause) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  step(1.0);
  hear(0, 1.1, "t1", AgentTask::Running, "running");
  live_.agents[0].failsafe = "none";
  step(1.1);
  const std::size_t before = store_->history("t1").size();
  hear(0, 1.2, "t1", AgentTask::Running, "failsafe emergency-hover: relative-state-stale of G1");
  live_.agents[0].failsafe = "emergency-hover";
  step(1.2);
  step(1.25);  // the same report again: no second row
  hear(0, 1.6, "t1", AgentTask::Running, "failsafe cleared (was emergency-hover)");
  live_.agents[0].failsafe = "none";
  step(1.6);
  const auto history = store_->history("t1");
  ASSERT_EQ(history.size(), before + 2);
  EXPECT_EQ(history[before].from, TaskState::Running);
  EXPECT_EQ(history[before].to, TaskState::Running);
  EXPECT_EQ(history[before].reason,
            "UAV 0 failsafe none -> emergency-hover: failsafe emergency-hover: "
            "relative-state-stale of G1");
  EXPECT_EQ(history[before + 1].time_s, 1.6);
  EXPECT_EQ(state("t1"), TaskState::Running);
}

TEST_F(DispatcherTest, AnAgentBackIdleFailsItsRunningTask) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  submit("t2", 0, 1.0);
  step(1.0);
  hear(0, 1.5, "t1", AgentTask::Running);
  step(1.5);
  hear(0, 2.0);  // the agent restarted: no task
  const Actions actions = step(2.0);
  EXPECT_EQ(state("t1"), TaskState::Failed);
  EXPECT_EQ(reason("t1"), "UAV 0 came back idle");
  ASSERT_EQ(actions.dispatch.size(), 1u);
  EXPECT_EQ(actions.dispatch[0].record.task_id, "t2");
}

TEST_F(DispatcherTest, AfterARestartARunningTaskIsRelearnedAndNeverDispatchedTwice) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  submit("t2", 0, 1.0);
  step(1.0);
  hear(0, 1.5, "t1", AgentTask::Running);
  step(1.5);
  ASSERT_EQ(state("t1"), TaskState::Running);

  restart();
  live_ = LiveView{};  // the new process has heard nothing yet
  EXPECT_TRUE(step(10.0).dispatch.empty());
  step(11.9);  // within one heartbeat timeout of starting: wait for the reports
  EXPECT_EQ(state("t1"), TaskState::Running);
  hear(0, 12.0, "t1", AgentTask::Running);
  for (double t = 12.0; t < 20.0; t += 0.5) {
    hear_again(0, t);
    const Actions actions = step(t);
    EXPECT_TRUE(actions.dispatch.empty()) << "t = " << t;
  }
  hear(0, 20.0, "t1", AgentTask::Succeeded, "landed");
  const Actions actions = step(20.0);
  EXPECT_EQ(state("t1"), TaskState::Succeeded);
  EXPECT_EQ(reason("t1"), "landed");
  ASSERT_EQ(actions.dispatch.size(), 1u);
  EXPECT_EQ(actions.dispatch[0].record.task_id, "t2");
  EXPECT_EQ(store_->history("t1").size(), 4u);  // queued, dispatched, running, succeeded
}

TEST_F(DispatcherTest, AfterARestartADispatchedTaskFinishesWithTheAgentsTrueResult) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  step(1.0);
  restart();
  hear(0, 2.0, "t1", AgentTask::Failed, "planning failed");
  EXPECT_TRUE(step(2.0).dispatch.empty());
  EXPECT_EQ(state("t1"), TaskState::Failed);
  EXPECT_EQ(reason("t1"), "planning failed");
}

TEST_F(DispatcherTest, ASilentAgentAfterARestartFailsOnceTheTimeoutHasPassed) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  step(1.0);
  hear(0, 1.5, "t1", AgentTask::Running);
  step(1.5);
  restart();
  live_ = LiveView{};
  step(100.0);
  EXPECT_EQ(state("t1"), TaskState::Running);
  // Within the restart grace (10 s) an agent not heard yet is not silent: discovery of the
  // restarted manager can take seconds.
  step(109.0);
  EXPECT_EQ(state("t1"), TaskState::Running);
  step(110.5);
  EXPECT_EQ(state("t1"), TaskState::Failed);
  EXPECT_EQ(reason("t1"), "UAV 0 went silent (no heartbeat for 1.5 s)");
}

TEST_F(DispatcherTest, ADispatchTheAgentNeverTakesFailsAfterTheDispatchTimeout) {
  hear(0, 1.0, "previous", AgentTask::Succeeded);
  submit("t1", 0, 1.0);
  submit("t2", 0, 1.0);
  ASSERT_EQ(step(1.0).dispatch.size(), 1u);
  int resent = 0;
  for (double t = 1.5; t <= 6.0; t += 0.5) {
    hear_again(0, t);
    // The agent looks idle (it reports its previous task done): t1 may have been lost on
    // its way, so it is sent again, once a second, and nothing else is sent meanwhile.
    for (const Dispatch& d : step(t).dispatch) {
      EXPECT_EQ(d.record.task_id, "t1") << "t = " << t;
      ++resent;
    }
    EXPECT_EQ(state("t1"), TaskState::Dispatched) << "t = " << t;
  }
  EXPECT_EQ(resent, 5);  // at 2, 3, 4, 5 and 6 s
  hear_again(0, 6.1);
  const Actions actions = step(6.1);
  EXPECT_EQ(state("t1"), TaskState::Failed);
  EXPECT_EQ(reason("t1"), "UAV 0 did not take the task within 5.0 s");
  ASSERT_EQ(actions.dispatch.size(), 1u);
  EXPECT_EQ(actions.dispatch[0].record.task_id, "t2");
}

TEST_F(DispatcherTest, ADispatchTheAgentRejectsIsRejectedWithItsReason) {
  hear(0, 1.0);
  submit("t1", 0, 1.0);
  step(1.0);
  hear(0, 1.2, "t1", AgentTask::Rejected, "unknown UGV 1");
  step(1.2);
  EXPECT_EQ(state("t1"), TaskState::Rejected);
  EXPECT_EQ(reason("t1"), "unknown UGV 1");
}

TEST_F(DispatcherTest, TwoHundredTasksAreDispatchedExactlyOnceEachInOrder) {
  constexpr int kTasks = 200;
  hear(0, 0.0);
  for (int i = 0; i < kTasks; ++i) submit("t" + std::to_string(i), 0, 0.0);
  std::vector<std::string> dispatched;
  double t = 0.0;
  for (int round = 0; round < 3 * kTasks && dispatched.size() <= kTasks; ++round) {
    t += 0.1;
    hear_again(0, t);
    const Actions actions = step(t);
    ASSERT_LE(actions.dispatch.size(), 1u);
    for (const Dispatch& d : actions.dispatch) dispatched.push_back(d.record.task_id);
    // The agent alternates: take the last task sent, then report it done.
    const AgentReport& now = live_.agents[0];
    if (!actions.dispatch.empty()) {
      hear(0, t, actions.dispatch[0].record.task_id, AgentTask::Running);
    } else if (now.task_state == AgentTask::Running) {
      hear(0, t, now.task_id, AgentTask::Succeeded);
    } else if (dispatched.size() == kTasks) {
      break;
    }
  }
  ASSERT_EQ(dispatched.size(), static_cast<std::size_t>(kTasks));
  for (int i = 0; i < kTasks; ++i) EXPECT_EQ(dispatched[i], "t" + std::to_string(i));
  step(t + 0.1);
  for (const TaskRecord& r : store_->list(true)) {
    EXPECT_EQ(r.state, TaskState::Succeeded) << r.task_id;
    EXPECT_EQ(store_->history(r.task_id).size(), 4u) << r.task_id;
  }
}

}  // namespace
}  // namespace cover::task_manager
