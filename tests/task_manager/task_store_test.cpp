#include "cover/task_manager/task_store.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cover/task_manager/task_json.hpp"
#include "test_support.hpp"

namespace cover::task_manager {
namespace {
using testing::make_task;
using testing::RawDb;

class TaskStoreTest : public ::testing::Test {
 protected:
  std::string path() const { return dir_.file("tasks.db"); }
  testing::TempDir dir_;
};

void expect_same_record(const TaskRecord& a, const TaskRecord& b) {
  EXPECT_EQ(a.task_id, b.task_id);
  EXPECT_EQ(a.uav_id, b.uav_id);
  EXPECT_EQ(a.queue_position, b.queue_position);
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.submitter, b.submitter);
  EXPECT_EQ(a.request_id, b.request_id);
  EXPECT_EQ(a.submitted_s, b.submitted_s);
  EXPECT_EQ(a.updated_s, b.updated_s);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.task.task_id, b.task.task_id);
  EXPECT_EQ(a.task.uav_id, b.task.uav_id);
  ASSERT_EQ(a.task.processes.size(), b.task.processes.size());
  for (std::size_t i = 0; i < a.task.processes.size(); ++i) {
    const auto& p = a.task.processes[i];
    const auto& q = b.task.processes[i];
    EXPECT_EQ(p.from_ugv, q.from_ugv);
    EXPECT_EQ(p.to_ugv, q.to_ugv);
    EXPECT_EQ(p.initial_point_m, q.initial_point_m);
    EXPECT_EQ(p.transition_point_m, q.transition_point_m);
    EXPECT_EQ(p.final_point_m, q.final_point_m);
    EXPECT_EQ(p.final_action, q.final_action);
    EXPECT_EQ(p.vmax_m_s, q.vmax_m_s);
    EXPECT_EQ(p.amax_m_s2, q.amax_m_s2);
  }
}

mission::Task two_process_task() {
  mission::Task task = make_task("round-trip", 2);
  task.processes[0].final_action = mission::FinalAction::Deliver;
  task.processes[0].vmax_m_s = 1.0 / 3.0;
  task.processes[0].amax_m_s2 = 2.5;
  mission::TransitionProcess back = task.processes[0];
  back.from_ugv = 1;
  back.to_ugv = 0;
  back.initial_point_m = {1.25, -2.0, 2.0};
  back.transition_point_m = {0.1, 0.2, 0.3};
  back.final_point_m = {-0.01, 0.02, 0.25};
  back.final_action = mission::FinalAction::Land;
  task.processes.push_back(back);
  return task;
}

TEST_F(TaskStoreTest, EveryFieldRoundTripsThroughFindAndList) {
  TaskStore store(path());
  const auto result = store.submit(two_process_task(), "alice@gs", "req-7", TaskState::Queued,
                                   "queued for UAV 2", 1767225600.123456);
  ASSERT_TRUE(result.created);
  EXPECT_EQ(result.record.task_id, "round-trip");
  EXPECT_EQ(result.record.uav_id, 2);
  EXPECT_EQ(result.record.submitter, "alice@gs");
  EXPECT_EQ(result.record.request_id, "req-7");
  EXPECT_EQ(result.record.updated_s, 1767225600.123456);
  const auto found = store.find("round-trip");
  ASSERT_TRUE(found.has_value());
  expect_same_record(result.record, *found);
  EXPECT_EQ(found->task.processes[1].final_action, mission::FinalAction::Land);
  const auto listed = store.list(true);
  ASSERT_EQ(listed.size(), 1u);
  expect_same_record(result.record, listed[0]);
  EXPECT_FALSE(store.find("other").has_value());
}

TEST_F(TaskStoreTest, SubmitIsIdempotentByTaskId) {
  TaskStore store(path());
  const auto first = store.submit(make_task("t1"), "alice", "r1", TaskState::Queued, "", 10.0);
  mission::Task changed = make_task("t1", 5);
  changed.processes[0].vmax_m_s = 2.0;
  const auto again = store.submit(changed, "bob", "r2", TaskState::Rejected, "nope", 20.0);
  EXPECT_TRUE(first.created);
  EXPECT_FALSE(again.created);
  expect_same_record(first.record, again.record);
  expect_same_record(first.record, *store.find("t1"));
  EXPECT_EQ(store.history("t1").size(), 1u);
  EXPECT_EQ(store.list(true).size(), 1u);
}

TEST_F(TaskStoreTest, QueuePositionsIncreaseInSubmissionOrderAcrossUavsAndStates) {
  TaskStore store(path());
  std::int64_t last = 0;
  for (int i = 0; i < 6; ++i) {
    const auto initial = i == 3 ? TaskState::Rejected : TaskState::Queued;
    const auto r = store.submit(make_task("t" + std::to_string(i), i % 2), "s", "", initial,
                                initial == TaskState::Rejected ? "bad" : "", i);
    EXPECT_GT(r.record.queue_position, last);
    last = r.record.queue_position;
  }
  const auto all = store.list(true);
  ASSERT_EQ(all.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(all[i].task_id, "t" + std::to_string(i));
  EXPECT_EQ(store.list(false).size(), 5u);  // the rejected one is final
  ASSERT_TRUE(store.next_queued(1).has_value());
  EXPECT_EQ(store.next_queued(1)->task_id, "t1");
  EXPECT_EQ(store.next_queued(0)->task_id, "t0");
  EXPECT_FALSE(store.next_queued(7).has_value());
  store.set_state("t0", TaskState::Dispatched, "sent", 7.0);
  EXPECT_EQ(store.next_queued(0)->task_id, "t2");
  const auto dispatched_or_rejected = store.in_states({TaskState::Rejected, TaskState::Dispatched});
  ASSERT_EQ(dispatched_or_rejected.size(), 2u);
  EXPECT_EQ(dispatched_or_rejected[0].task_id, "t0");
  EXPECT_EQ(dispatched_or_rejected[1].task_id, "t3");
  EXPECT_EQ(dispatched_or_rejected[1].reason, "bad");
}

TEST_F(TaskStoreTest, HistoryIsOldestFirstStartingWithTheSubmission) {
  TaskStore store(path());
  store.submit(make_task("t"), "s", "", TaskState::Queued, "queued", 1.0);
  EXPECT_TRUE(store.set_state("t", TaskState::Dispatched, "sent", 2.0));
  EXPECT_TRUE(store.set_state("t", TaskState::Running, "taken", 3.0));
  EXPECT_TRUE(store.set_state("t", TaskState::Succeeded, "landed", 4.0));
  const auto h = store.history("t");
  ASSERT_EQ(h.size(), 4u);
  EXPECT_EQ(h[0].from, TaskState::Queued);
  EXPECT_EQ(h[0].to, TaskState::Queued);
  EXPECT_EQ(h[0].reason, "queued");
  const TaskState to[] = {TaskState::Queued, TaskState::Dispatched, TaskState::Running,
                          TaskState::Succeeded};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(h[i].task_id, "t");
    EXPECT_EQ(h[i].to, to[i]);
    EXPECT_EQ(h[i].time_s, 1.0 + i);
    if (i > 0) {
      EXPECT_EQ(h[i].from, to[i - 1]);
    }
  }
  const auto record = store.find("t");
  EXPECT_EQ(record->state, TaskState::Succeeded);
  EXPECT_EQ(record->reason, "landed");
  EXPECT_EQ(record->updated_s, 4.0);
  EXPECT_EQ(record->submitted_s, 1.0);
}

TEST_F(TaskStoreTest, FinalStatesAndNoOpsRefuseChangesAndWriteNothing) {
  TaskStore store(path());
  int n = 0;
  for (const TaskState final_state :
       {TaskState::Succeeded, TaskState::Failed, TaskState::Aborted, TaskState::Rejected}) {
    const std::string id = "t" + std::to_string(n++);
    store.submit(make_task(id), "s", "", TaskState::Queued, "", 1.0);
    ASSERT_TRUE(store.set_state(id, final_state, "end", 2.0));
    for (const TaskState to : {TaskState::Queued, TaskState::Running, TaskState::Failed,
                               TaskState::Succeeded, final_state}) {
      EXPECT_FALSE(store.set_state(id, to, "again", 3.0)) << to_string(final_state);
    }
    EXPECT_EQ(store.history(id).size(), 2u);
    EXPECT_EQ(store.find(id)->state, final_state);
    EXPECT_EQ(store.find(id)->updated_s, 2.0);
  }
  store.submit(make_task("q"), "s", "", TaskState::Queued, "", 1.0);
  EXPECT_FALSE(store.set_state("q", TaskState::Queued, "same", 2.0));
  EXPECT_EQ(store.history("q").size(), 1u);
  EXPECT_THROW(store.set_state("nobody", TaskState::Running, "", 1.0), StoreError);
  EXPECT_THROW(store.submit(make_task("d"), "s", "", TaskState::Running, "", 1.0), StoreError);
  EXPECT_FALSE(store.find("d").has_value());
}

TEST_F(TaskStoreTest, SetReasonKeepsTheStateAndRecordsEachChangeOnce) {
  TaskStore store(path());
  store.submit(make_task("q"), "s", "r", TaskState::Queued, "queued for UAV 0", 1.0);
  EXPECT_TRUE(store.set_reason("q", "waiting for UAV 0: autopilot disarmed", 2.0));
  EXPECT_FALSE(store.set_reason("q", "waiting for UAV 0: autopilot disarmed", 3.0))
      << "the same reason again writes nothing";
  const auto record = store.find("q");
  EXPECT_EQ(record->state, TaskState::Queued);
  EXPECT_EQ(record->reason, "waiting for UAV 0: autopilot disarmed");
  EXPECT_EQ(record->updated_s, 2.0);
  const auto history = store.history("q");
  ASSERT_EQ(history.size(), 2u);
  EXPECT_EQ(history[1].from, TaskState::Queued);
  EXPECT_EQ(history[1].to, TaskState::Queued);
  EXPECT_EQ(history[1].reason, "waiting for UAV 0: autopilot disarmed");
  ASSERT_TRUE(store.set_state("q", TaskState::Aborted, "operator", 4.0));
  EXPECT_FALSE(store.set_reason("q", "late", 5.0)) << "a final task keeps its reason";
  EXPECT_EQ(store.find("q")->reason, "operator");
  EXPECT_THROW(store.set_reason("nobody", "x", 1.0), StoreError);
}

TEST_F(TaskStoreTest, RejectedSubmissionIsRecordedWithItsReason) {
  TaskStore store(path());
  const auto r = store.submit(make_task("bad"), "s", "r", TaskState::Rejected, "UGV 3 is down", 5);
  EXPECT_TRUE(r.created);
  EXPECT_EQ(store.find("bad")->state, TaskState::Rejected);
  EXPECT_EQ(store.find("bad")->reason, "UGV 3 is down");
  ASSERT_EQ(store.history("bad").size(), 1u);
  EXPECT_EQ(store.history("bad")[0].from, TaskState::Rejected);
  EXPECT_EQ(store.history("bad")[0].to, TaskState::Rejected);
}

// Issue 31: a submission rejected at once holds no id. The next one with its id replaces
// it, whatever its content; the rejected one is kept whole, its history stays the id's.
TEST_F(TaskStoreTest, ARejectedSubmissionIsReplacedByTheNextWithItsIdAndKept) {
  TaskStore store(path());
  mission::Task wrong = make_task("hop");
  wrong.processes[0].to_ugv = 7;
  const auto first =
      store.submit(wrong, "alice", "r1", TaskState::Rejected, "UGV 7 is not publishing", 1.0);
  EXPECT_TRUE(first.created);
  EXPECT_FALSE(first.replaced_rejected);
  EXPECT_FALSE(first.record.accepted);
  EXPECT_FALSE(store.find("hop")->accepted);
  const auto again =
      store.submit(wrong, "alice", "r2", TaskState::Rejected, "UGV 7 is still down", 2.0);
  EXPECT_TRUE(again.created);
  EXPECT_TRUE(again.replaced_rejected);
  EXPECT_GT(again.record.queue_position, first.record.queue_position);
  const auto corrected =
      store.submit(make_task("hop"), "bob", "r3", TaskState::Queued, "queued for UAV 0", 3.0);
  EXPECT_TRUE(corrected.created);
  EXPECT_TRUE(corrected.replaced_rejected);
  EXPECT_TRUE(corrected.record.accepted);
  expect_same_record(corrected.record, *store.find("hop"));
  EXPECT_EQ(store.find("hop")->task.processes[0].to_ugv, 1);
  EXPECT_EQ(store.list(true).size(), 1u);
  EXPECT_EQ(store.next_queued(0)->task_id, "hop");

  const auto kept = store.replaced_rejections("hop");
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].request_id, "r1");
  EXPECT_EQ(kept[0].reason, "UGV 7 is not publishing");
  EXPECT_EQ(kept[0].task.processes[0].to_ugv, 7);
  EXPECT_EQ(kept[0].submitted_s, 1.0);
  EXPECT_EQ(kept[0].queue_position, first.record.queue_position);
  EXPECT_EQ(kept[0].state, TaskState::Rejected);
  EXPECT_FALSE(kept[0].accepted);
  EXPECT_EQ(kept[1].request_id, "r2");
  EXPECT_EQ(kept[1].reason, "UGV 7 is still down");

  const auto history = store.history("hop");
  ASSERT_EQ(history.size(), 3u);
  EXPECT_EQ(history[0].from, TaskState::Rejected);
  EXPECT_EQ(history[0].to, TaskState::Rejected);
  EXPECT_EQ(history[0].reason, "UGV 7 is not publishing");
  EXPECT_EQ(history[1].from, TaskState::Rejected);
  EXPECT_EQ(history[1].to, TaskState::Rejected);
  EXPECT_EQ(history[2].from, TaskState::Rejected);
  EXPECT_EQ(history[2].to, TaskState::Queued);
  EXPECT_EQ(history[2].reason, "queued for UAV 0");

  // Accepted, it holds its id: another submission changes nothing.
  const auto held = store.submit(wrong, "carol", "r4", TaskState::Rejected, "no", 4.0);
  EXPECT_FALSE(held.created);
  expect_same_record(corrected.record, held.record);
  EXPECT_EQ(store.replaced_rejections("hop").size(), 2u);
  EXPECT_TRUE(store.replaced_rejections("other").empty());
}

// A version 1 file, as the previous release wrote it: a submission rejected at once, a task
// the UAV agent rejected, one queued. Opened, it is version 2 with every task, row and
// history kept; only the one rejected at once lets its id go.
TEST_F(TaskStoreTest, MigratesAVersion1FileKeepingEverythingAndFreeingOnlyIdsRejectedAtOnce) {
  {
    RawDb raw(path());
    raw.exec(
        "CREATE TABLE tasks (task_id TEXT PRIMARY KEY NOT NULL, uav_id INTEGER NOT NULL,"
        " queue_position INTEGER NOT NULL UNIQUE, state TEXT NOT NULL, submitter TEXT NOT NULL,"
        " request_id TEXT NOT NULL, task_json TEXT NOT NULL, submitted_s REAL NOT NULL,"
        " updated_s REAL NOT NULL, reason TEXT NOT NULL DEFAULT '');"
        "CREATE TABLE task_history (id INTEGER PRIMARY KEY, task_id TEXT NOT NULL REFERENCES"
        " tasks(task_id), from_state TEXT NOT NULL, to_state TEXT NOT NULL, time_s REAL NOT NULL,"
        " reason TEXT NOT NULL);"
        "CREATE TABLE schema_version (version INTEGER NOT NULL);"
        "INSERT INTO schema_version VALUES (1);");
    const auto task = [](const std::string& id) { return task_to_json(make_task(id)); };
    raw.exec("INSERT INTO tasks VALUES ('at-once', 0, 1, 'rejected', 'ops', 'r1', '" +
             task("at-once") + "', 10.0, 10.0, 'UGV 7 is not publishing its IMU')");
    raw.exec(
        "INSERT INTO task_history (task_id, from_state, to_state, time_s, reason) VALUES"
        " ('at-once', 'rejected', 'rejected', 10.0, 'UGV 7 is not publishing its IMU')");
    raw.exec("INSERT INTO tasks VALUES ('by-agent', 0, 2, 'rejected', 'ops', 'r2', '" +
             task("by-agent") + "', 11.0, 13.0, 'unknown UGV 1')");
    raw.exec(
        "INSERT INTO task_history (task_id, from_state, to_state, time_s, reason) VALUES"
        " ('by-agent', 'queued', 'queued', 11.0, 'queued for UAV 0'),"
        " ('by-agent', 'queued', 'dispatched', 12.0, 'sent'),"
        " ('by-agent', 'dispatched', 'rejected', 13.0, 'unknown UGV 1')");
    raw.exec("INSERT INTO tasks VALUES ('waiting', 0, 3, 'queued', 'ops', 'r3', '" +
             task("waiting") + "', 14.0, 14.0, 'queued for UAV 0')");
    raw.exec(
        "INSERT INTO task_history (task_id, from_state, to_state, time_s, reason) VALUES"
        " ('waiting', 'queued', 'queued', 14.0, 'queued for UAV 0')");
  }
  TaskStore store(path());
  EXPECT_EQ(store.schema_version(), 2);
  const auto all = store.list(true);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].task_id, "at-once");
  EXPECT_FALSE(all[0].accepted);
  EXPECT_EQ(all[0].reason, "UGV 7 is not publishing its IMU");
  EXPECT_EQ(all[0].request_id, "r1");
  EXPECT_EQ(all[1].task_id, "by-agent");
  EXPECT_TRUE(all[1].accepted);
  EXPECT_EQ(all[1].state, TaskState::Rejected);
  EXPECT_EQ(all[1].updated_s, 13.0);
  EXPECT_TRUE(all[2].accepted);
  EXPECT_EQ(store.history("at-once").size(), 1u);
  EXPECT_EQ(store.history("by-agent").size(), 3u);
  EXPECT_EQ(store.history("waiting").size(), 1u);

  EXPECT_TRUE(
      store.submit(make_task("at-once"), "ops", "r4", TaskState::Queued, "q", 20.0).created);
  EXPECT_EQ(store.replaced_rejections("at-once").at(0).reason, "UGV 7 is not publishing its IMU");
  EXPECT_FALSE(
      store.submit(make_task("by-agent"), "ops", "r5", TaskState::Queued, "q", 20.0).created)
      << "a task the agent rejected was accepted first: it holds its id";
  EXPECT_EQ(store.find("by-agent")->state, TaskState::Rejected);
}

TEST_F(TaskStoreTest, ReopenAfterCloseKeepsEverything) {
  TaskRecord before;
  {
    TaskStore store(path());
    store.submit(make_task("a"), "s", "", TaskState::Queued, "", 1.0);
    before = store.submit(two_process_task(), "bob", "r9", TaskState::Queued, "q", 2.0).record;
    store.set_state("a", TaskState::Dispatched, "sent", 3.0);
    store.set_state("round-trip", TaskState::Aborted, "operator", 4.0);
    before.state = TaskState::Aborted;
    before.reason = "operator";
    before.updated_s = 4.0;
  }
  TaskStore store(path());
  expect_same_record(before, *store.find("round-trip"));
  EXPECT_EQ(store.find("a")->state, TaskState::Dispatched);
  EXPECT_EQ(store.history("a").size(), 2u);
  EXPECT_EQ(store.history("round-trip").size(), 2u);
  const auto next = store.submit(make_task("c"), "s", "", TaskState::Queued, "", 5.0);
  EXPECT_GT(next.record.queue_position, before.queue_position);
}

TEST_F(TaskStoreTest, SchemaVersionTableIsCreatedAndStatesAreReadableText) {
  {
    TaskStore store(path());
    EXPECT_EQ(store.schema_version(), TaskStore::kSchemaVersion);
    store.submit(make_task("a"), "s", "", TaskState::Queued, "", 1.0);
  }
  RawDb raw(path());
  EXPECT_EQ(raw.scalar("SELECT version FROM schema_version"),
            std::to_string(TaskStore::kSchemaVersion));
  EXPECT_EQ(raw.scalar("SELECT COUNT(*) FROM schema_version"), "1");
  EXPECT_EQ(raw.scalar("SELECT state FROM tasks WHERE task_id = 'a'"), "queued");
  EXPECT_EQ(raw.scalar("SELECT to_state FROM task_history WHERE task_id = 'a'"), "queued");
}

TEST_F(TaskStoreTest, FileFromANewerSchemaIsRefused) {
  { TaskStore store(path()); }
  RawDb(path()).exec("UPDATE schema_version SET version = " +
                     std::to_string(TaskStore::kSchemaVersion + 1));
  try {
    TaskStore store(path());
    FAIL() << "opened a file from a newer schema";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("written by a newer version"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(path()), std::string::npos) << e.what();
  }
}

// Version 0: the pre-release layout, a tasks table without `reason`, no history, no version.
TEST_F(TaskStoreTest, MigratesAVersion0FileKeepingItsTasks) {
  {
    RawDb raw(path());
    raw.exec(
        "CREATE TABLE tasks (task_id TEXT PRIMARY KEY NOT NULL, uav_id INTEGER NOT NULL,"
        " queue_position INTEGER NOT NULL UNIQUE, state TEXT NOT NULL, submitter TEXT NOT NULL,"
        " request_id TEXT NOT NULL, task_json TEXT NOT NULL, submitted_s REAL NOT NULL,"
        " updated_s REAL NOT NULL)");
    raw.exec("INSERT INTO tasks VALUES ('old-1', 0, 1, 'succeeded', 'ops', 'r', '" +
             task_to_json(make_task("old-1")) + "', 100.0, 150.0)");
    raw.exec("INSERT INTO tasks VALUES ('old-2', 1, 2, 'queued', 'ops', 'r', '" +
             task_to_json(make_task("old-2", 1)) + "', 110.0, 110.0)");
  }
  TaskStore store(path());
  EXPECT_EQ(store.schema_version(), TaskStore::kSchemaVersion);
  const auto old = store.find("old-1");
  ASSERT_TRUE(old.has_value());
  EXPECT_EQ(old->state, TaskState::Succeeded);
  EXPECT_EQ(old->reason, "");
  EXPECT_EQ(old->updated_s, 150.0);
  EXPECT_EQ(old->task.processes.size(), 1u);
  ASSERT_EQ(store.history("old-2").size(), 1u);
  EXPECT_EQ(store.history("old-2")[0].to, TaskState::Queued);
  EXPECT_EQ(store.history("old-2")[0].time_s, 110.0);
  EXPECT_TRUE(store.set_state("old-2", TaskState::Dispatched, "sent", 200.0));
  EXPECT_EQ(
      store.submit(make_task("new"), "s", "", TaskState::Queued, "", 300).record.queue_position, 3);
}

TEST_F(TaskStoreTest, MigratesAnEmptyFile) {
  std::ofstream(path()).close();
  ASSERT_TRUE(std::filesystem::exists(path()));
  TaskStore store(path());
  EXPECT_EQ(store.schema_version(), TaskStore::kSchemaVersion);
  EXPECT_TRUE(store.list(true).empty());
}

TEST_F(TaskStoreTest, WalAndSynchronousFullAndForeignKeysAreInEffect) {
  TaskStore store(path());
  EXPECT_EQ(store.pragma("journal_mode"), "wal");
  EXPECT_EQ(store.pragma("synchronous"), "2");  // FULL
  EXPECT_EQ(store.pragma("foreign_keys"), "1");
  EXPECT_NE(store.pragma("busy_timeout"), "0");
  EXPECT_THROW(store.pragma("journal_mode = DELETE"), StoreError);
  RawDb raw(path());
  EXPECT_EQ(raw.scalar("PRAGMA journal_mode"), "wal");  // WAL is a property of the file
  EXPECT_THROW(raw.exec("PRAGMA foreign_keys = ON; INSERT INTO task_history (task_id, from_state,"
                        " to_state, time_s, reason) VALUES ('ghost', 'queued', 'queued', 0, '')"),
               std::runtime_error);
}

TEST_F(TaskStoreTest, UnopenableFileThrowsStoreErrorNamingThePath) {
  const std::string bad = dir_.file("no-such-dir/tasks.db");
  try {
    TaskStore store(bad);
    FAIL() << "opened " << bad;
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  std::ofstream(path()) << "this is not a database, it is a text file of some length...........";
  EXPECT_THROW(TaskStore store(path()), StoreError);
}

}  // namespace
}  // namespace cover::task_manager
