#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "cover/task_manager/store_error.hpp"
#include "cover/task_manager/task_record.hpp"
#include "cover/task_manager/task_state.hpp"
#include "cover/vocabulary/task.hpp"

struct sqlite3;

namespace cover::task_manager {

// Tasks and their state history in one SQLite file. Every public write is one transaction
// (BEGIN IMMEDIATE ... COMMIT), the journal is WAL with synchronous=FULL: once a write has
// returned it survives a crash of the process or the machine, and a crash mid-write leaves
// all or nothing. Not thread-safe: one TaskStore per thread (several processes may share a
// file; SQLite serialises them, waiting up to the busy timeout).
class TaskStore {
 public:
  static constexpr int kSchemaVersion = 2;

  // Opens or creates the file and creates or migrates its schema. Throws StoreError (with
  // SQLite's message and the path) when it cannot, or when a newer version wrote the file.
  // ":memory:" is a store in memory only (tests, fuzzing): nothing survives the process.
  explicit TaskStore(const std::string& path);
  ~TaskStore();
  TaskStore(const TaskStore&) = delete;
  TaskStore& operator=(const TaskStore&) = delete;

  int schema_version() const;
  // The value of a PRAGMA on this connection (e.g. "journal_mode", "synchronous"): some are
  // per connection, so only the store's own connection can show they are in effect. `name`
  // must be a plain identifier; anything else throws StoreError.
  std::string pragma(const std::string& name) const;
  const std::string& path() const { return path_; }

  struct SubmitResult {
    bool created = false;
    // It replaced a submission rejected under the same id (kept: rejected_submissions).
    bool replaced_rejected = false;
    TaskRecord record;
  };
  // Idempotent by task_id for accepted tasks: the id of a task accepted (queued) at
  // submission again returns the stored record, created = false, and changes nothing. A
  // submission rejected at once holds no id: the next one with its id replaces it (the
  // rejected one moves to rejected_submissions, its history stays the id's, followed by a
  // row from rejected to the new initial state). `initial` is Queued or Rejected (a
  // rejected submission is recorded too, with its reason); anything else throws StoreError.
  SubmitResult submit(const mission::Task& task, const std::string& submitter,
                      const std::string& request_id, TaskState initial, const std::string& reason,
                      double now_s);

  // Updates the record and appends a history row, in one transaction. Returns false, and
  // writes nothing, when the task is already final or `to` is its current state. Throws
  // StoreError for an unknown id.
  bool set_state(const std::string& task_id, TaskState to, const std::string& reason, double now_s);
  // Appends a history row that keeps the state (from = to: an event such as a UAV's
  // failsafe entry or exit). Returns false, and writes nothing, when the task is final.
  // Throws StoreError for an unknown id.
  bool note(const std::string& task_id, const std::string& reason, double now_s);
  // Makes `reason` the task's current reason (and updated_s `now_s`), keeping its state, and
  // appends it as a history row, in one transaction: what a queued task waits for. Returns
  // false, and writes nothing, when the task is final or `reason` is already its reason.
  // Throws StoreError for an unknown id.
  bool set_reason(const std::string& task_id, const std::string& reason, double now_s);

  std::optional<TaskRecord> find(const std::string& task_id) const;
  std::vector<TaskRecord> list(bool include_final) const;                            // queue order
  std::vector<TaskRecord> in_states(std::initializer_list<TaskState> states) const;  // queue order
  std::optional<TaskRecord> next_queued(int uav_id) const;  // lowest queue_position, Queued
  std::vector<StateChange> history(const std::string& task_id) const;  // oldest first
  // The rejected submissions later ones with the same id replaced, oldest first (state
  // Rejected, accepted false, updated_s their submission time).
  std::vector<TaskRecord> replaced_rejections(const std::string& task_id) const;

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

}  // namespace cover::task_manager
