#include "cover/task_manager/task_store.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cctype>

#include "cover/task_manager/task_json.hpp"
#include "schema.hpp"
#include "sqlite_db.hpp"

namespace cover::task_manager {
namespace {

// Another process holding the write lock (a second manager, the sqlite3 CLI) is waited for
// this long before a write fails with "database is locked".
constexpr int kBusyTimeout_ms = 5000;

constexpr const char* kRecordColumns =
    "SELECT task_id, uav_id, queue_position, state, submitter, request_id, task_json,"
    " submitted_s, updated_s, reason, accepted FROM tasks ";

TaskState state_from_text(const std::string& text) {
  const auto state = parse_task_state(text);
  if (!state) throw StoreError("task store: unknown state '" + text + "' in the file");
  return *state;
}

TaskRecord read_record(const sqlite::Statement& row) {
  TaskRecord record;
  record.task_id = row.text(0);
  record.uav_id = static_cast<int>(row.integer(1));
  record.queue_position = row.integer(2);
  record.state = state_from_text(row.text(3));
  record.submitter = row.text(4);
  record.request_id = row.text(5);
  record.task = task_from_json(row.text(6));
  record.submitted_s = row.real(7);
  record.updated_s = row.real(8);
  record.reason = row.text(9);
  record.accepted = row.integer(10) != 0;
  return record;
}

std::vector<TaskRecord> read_records(sqlite::Statement& query) {
  std::vector<TaskRecord> records;
  while (query.step()) records.push_back(read_record(query));
  return records;
}

void append_history(sqlite3* db, const std::string& task_id, TaskState from, TaskState to,
                    double time_s, const std::string& reason) {
  sqlite::Statement insert(db,
                           "INSERT INTO task_history (task_id, from_state, to_state, time_s,"
                           " reason) VALUES (?, ?, ?, ?, ?)");
  insert.bind(1, task_id)
      .bind(2, std::string(to_string(from)))
      .bind(3, std::string(to_string(to)))
      .bind(4, time_s)
      .bind(5, reason)
      .run();
}

std::int64_t next_queue_position(sqlite3* db) {
  sqlite::Statement query(db, "SELECT COALESCE(MAX(queue_position), 0) + 1 FROM tasks");
  query.step();
  return query.integer(0);
}

// INSERT or, for a record that replaces a rejected submission, UPDATE: the same columns.
void write_record(sqlite3* db, const TaskRecord& r, bool replace) {
  const char* sql = replace
                        ? "UPDATE tasks SET uav_id = ?2, queue_position = ?3, state = ?4,"
                          " submitter = ?5, request_id = ?6, task_json = ?7, submitted_s = ?8,"
                          " updated_s = ?9, reason = ?10, accepted = ?11 WHERE task_id = ?1"
                        : "INSERT INTO tasks (task_id, uav_id, queue_position, state, submitter,"
                          " request_id, task_json, submitted_s, updated_s, reason, accepted)"
                          " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)";
  sqlite::Statement write(db, sql);
  write.bind(1, r.task_id)
      .bind(2, r.uav_id)
      .bind(3, r.queue_position)
      .bind(4, std::string(to_string(r.state)))
      .bind(5, r.submitter)
      .bind(6, r.request_id)
      .bind(7, task_to_json(r.task))
      .bind(8, r.submitted_s)
      .bind(9, r.updated_s)
      .bind(10, r.reason)
      .bind(11, r.accepted ? 1 : 0)
      .run();
}

// The rejected submission a new one replaces, kept whole.
void keep_rejected(sqlite3* db, const std::string& task_id) {
  sqlite::Statement copy(db,
                         "INSERT INTO rejected_submissions (task_id, uav_id, queue_position,"
                         " submitter, request_id, task_json, submitted_s, reason)"
                         " SELECT task_id, uav_id, queue_position, submitter, request_id,"
                         " task_json, submitted_s, reason FROM tasks WHERE task_id = ?");
  copy.bind(1, task_id).run();
}

// Connection settings are per connection, so they are set on every open. WAL lets readers
// (the ground station, the CLI) read while the manager writes; synchronous=FULL makes a
// committed transaction durable across a power cut, not only a process crash.
// An in-memory store (path ":memory:", for tests and fuzzing) has no file to journal to:
// SQLite keeps its journal in memory, and there is nothing to make durable.
void configure(sqlite3* db, bool in_memory) {
  sqlite3_busy_timeout(db, kBusyTimeout_ms);
  sqlite::exec(db, "PRAGMA foreign_keys = ON");
  if (in_memory) return;
  sqlite::Statement journal(db, "PRAGMA journal_mode = WAL");
  if (!journal.step() || journal.text(0) != "wal") {
    sqlite::fail(db, "cannot switch to WAL journal (got '" + journal.text(0) + "')");
  }
  sqlite::exec(db, "PRAGMA synchronous = FULL");
}
}  // namespace

TaskStore::TaskStore(const std::string& path) : path_(path) {
  const int rc =
      sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  try {
    if (rc != SQLITE_OK) sqlite::fail(db_, "cannot open");
    configure(db_, path == ":memory:");
    schema::migrate(db_, kSchemaVersion);
  } catch (const StoreError& e) {
    sqlite3_close(db_);
    db_ = nullptr;
    const std::string what = e.what();
    // SQLite names no file in some messages (e.g. opening a directory); make sure it is there.
    throw StoreError(what.find(path) == std::string::npos ? path + ": " + what : what);
  }
}

TaskStore::~TaskStore() {
  sqlite3_close(db_);
}

int TaskStore::schema_version() const {
  return schema::read_version(db_);
}

std::string TaskStore::pragma(const std::string& name) const {
  const bool identifier = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
  if (!identifier) throw StoreError("task store: '" + name + "' is not a pragma name");
  sqlite::Statement query(db_, ("PRAGMA " + name).c_str());
  return query.step() ? query.text(0) : std::string();
}

TaskStore::SubmitResult TaskStore::submit(const mission::Task& task, const std::string& submitter,
                                          const std::string& request_id, TaskState initial,
                                          const std::string& reason, double now_s) {
  if (initial != TaskState::Queued && initial != TaskState::Rejected) {
    throw StoreError("task '" + task.task_id + "': a submission starts queued or rejected, not " +
                     to_string(initial));
  }
  sqlite::Transaction transaction(db_);
  const auto existing = find(task.task_id);
  if (existing && existing->accepted) return {false, false, std::move(*existing)};
  TaskRecord record;
  record.task_id = task.task_id;
  record.uav_id = task.uav_id;
  record.queue_position = next_queue_position(db_);
  record.state = initial;
  record.submitter = submitter;
  record.request_id = request_id;
  record.task = task;
  record.submitted_s = now_s;
  record.updated_s = now_s;
  record.reason = reason;
  record.accepted = initial == TaskState::Queued;
  if (existing) keep_rejected(db_, task.task_id);
  write_record(db_, record, existing.has_value());
  append_history(db_, record.task_id, existing ? existing->state : initial, initial, now_s, reason);
  transaction.commit();
  return {true, existing.has_value(), std::move(record)};
}

bool TaskStore::set_state(const std::string& task_id, TaskState to, const std::string& reason,
                          double now_s) {
  sqlite::Transaction transaction(db_);
  sqlite::Statement query(db_, "SELECT state FROM tasks WHERE task_id = ?");
  if (!query.bind(1, task_id).step()) {
    throw StoreError(path_ + ": no task '" + task_id + "'");
  }
  const TaskState from = state_from_text(query.text(0));
  if (is_final(from) || from == to) return false;
  sqlite::Statement update(db_,
                           "UPDATE tasks SET state = ?, updated_s = ?, reason = ?"
                           " WHERE task_id = ?");
  update.bind(1, std::string(to_string(to))).bind(2, now_s).bind(3, reason).bind(4, task_id).run();
  append_history(db_, task_id, from, to, now_s, reason);
  transaction.commit();
  return true;
}

bool TaskStore::note(const std::string& task_id, const std::string& reason, double now_s) {
  sqlite::Transaction transaction(db_);
  sqlite::Statement query(db_, "SELECT state FROM tasks WHERE task_id = ?");
  if (!query.bind(1, task_id).step()) {
    throw StoreError(path_ + ": no task '" + task_id + "'");
  }
  const TaskState state = state_from_text(query.text(0));
  if (is_final(state)) return false;
  append_history(db_, task_id, state, state, now_s, reason);
  transaction.commit();
  return true;
}

bool TaskStore::set_reason(const std::string& task_id, const std::string& reason, double now_s) {
  sqlite::Transaction transaction(db_);
  sqlite::Statement query(db_, "SELECT state, reason FROM tasks WHERE task_id = ?");
  if (!query.bind(1, task_id).step()) {
    throw StoreError(path_ + ": no task '" + task_id + "'");
  }
  const TaskState state = state_from_text(query.text(0));
  if (is_final(state) || query.text(1) == reason) return false;
  sqlite::Statement update(db_, "UPDATE tasks SET updated_s = ?, reason = ? WHERE task_id = ?");
  update.bind(1, now_s).bind(2, reason).bind(3, task_id).run();
  append_history(db_, task_id, state, state, now_s, reason);
  transaction.commit();
  return true;
}

std::optional<TaskRecord> TaskStore::find(const std::string& task_id) const {
  sqlite::Statement query(db_, (std::string(kRecordColumns) + "WHERE task_id = ?").c_str());
  if (!query.bind(1, task_id).step()) return std::nullopt;
  return read_record(query);
}

std::vector<TaskRecord> TaskStore::list(bool include_final) const {
  if (!include_final) {
    return in_states({TaskState::Queued, TaskState::Dispatched, TaskState::Running});
  }
  sqlite::Statement query(db_, (std::string(kRecordColumns) + "ORDER BY queue_position").c_str());
  return read_records(query);
}

std::vector<TaskRecord> TaskStore::in_states(std::initializer_list<TaskState> states) const {
  // Seven states at most: one placeholder each keeps the query a single prepared statement.
  std::string sql = std::string(kRecordColumns) + "WHERE state IN (";
  for (std::size_t i = 0; i < states.size(); ++i) sql += i == 0 ? "?" : ", ?";
  sql += ") ORDER BY queue_position";
  sqlite::Statement query(db_, sql.c_str());
  int index = 1;
  for (const TaskState state : states) query.bind(index++, std::string(to_string(state)));
  return read_records(query);
}

std::optional<TaskRecord> TaskStore::next_queued(int uav_id) const {
  sqlite::Statement query(db_, (std::string(kRecordColumns) +
                                "WHERE uav_id = ? AND state = ? ORDER BY queue_position LIMIT 1")
                                   .c_str());
  if (!query.bind(1, uav_id).bind(2, std::string(to_string(TaskState::Queued))).step()) {
    return std::nullopt;
  }
  return read_record(query);
}

std::vector<StateChange> TaskStore::history(const std::string& task_id) const {
  sqlite::Statement query(db_,
                          "SELECT from_state, to_state, time_s, reason FROM task_history"
                          " WHERE task_id = ? ORDER BY id");
  query.bind(1, task_id);
  std::vector<StateChange> changes;
  while (query.step()) {
    changes.push_back({task_id, state_from_text(query.text(0)), state_from_text(query.text(1)),
                       query.real(2), query.text(3)});
  }
  return changes;
}

std::vector<TaskRecord> TaskStore::replaced_rejections(const std::string& task_id) const {
  sqlite::Statement query(db_,
                          "SELECT uav_id, queue_position, submitter, request_id, task_json,"
                          " submitted_s, reason FROM rejected_submissions WHERE task_id = ?"
                          " ORDER BY id");
  query.bind(1, task_id);
  std::vector<TaskRecord> records;
  while (query.step()) {
    TaskRecord r;
    r.task_id = task_id;
    r.uav_id = static_cast<int>(query.integer(0));
    r.queue_position = query.integer(1);
    r.state = TaskState::Rejected;
    r.submitter = query.text(2);
    r.request_id = query.text(3);
    r.task = task_from_json(query.text(4));
    r.submitted_s = query.real(5);
    r.updated_s = r.submitted_s;
    r.reason = query.text(6);
    r.accepted = false;
    records.push_back(std::move(r));
  }
  return records;
}

}  // namespace cover::task_manager
