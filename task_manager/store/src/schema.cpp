#include "schema.hpp"

#include <string>
#include <vector>

#include "cover/task_manager/store_error.hpp"
#include "sqlite_db.hpp"

namespace cover::task_manager::schema {
namespace {

bool table_exists(sqlite3* db, const char* name) {
  sqlite::Statement query(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  return query.bind(1, std::string(name)).step();
}

bool column_exists(sqlite3* db, const char* table, const char* column) {
  sqlite::Statement query(db, "SELECT 1 FROM pragma_table_info(?) WHERE name = ?");
  return query.bind(1, std::string(table)).bind(2, std::string(column)).step();
}

// Version 1: tasks with the reason of their last change, their history, the version table.
// From the pre-release layout it adds `reason` and gives every old task its submission row,
// so "every task has a history starting with its submission" holds for old files too.
void to_version_1(sqlite3* db) {
  sqlite::exec(db,
               "CREATE TABLE IF NOT EXISTS tasks ("
               " task_id TEXT PRIMARY KEY NOT NULL,"
               " uav_id INTEGER NOT NULL,"
               " queue_position INTEGER NOT NULL UNIQUE,"
               " state TEXT NOT NULL,"
               " submitter TEXT NOT NULL,"
               " request_id TEXT NOT NULL,"
               " task_json TEXT NOT NULL,"
               " submitted_s REAL NOT NULL,"
               " updated_s REAL NOT NULL,"
               " reason TEXT NOT NULL DEFAULT '')");
  if (!column_exists(db, "tasks", "reason")) {
    sqlite::exec(db, "ALTER TABLE tasks ADD COLUMN reason TEXT NOT NULL DEFAULT ''");
  }
  sqlite::exec(db,
               "CREATE TABLE IF NOT EXISTS task_history ("
               " id INTEGER PRIMARY KEY,"
               " task_id TEXT NOT NULL REFERENCES tasks(task_id),"
               " from_state TEXT NOT NULL,"
               " to_state TEXT NOT NULL,"
               " time_s REAL NOT NULL,"
               " reason TEXT NOT NULL)");
  sqlite::exec(db,
               "INSERT INTO task_history (task_id, from_state, to_state, time_s, reason)"
               " SELECT task_id, state, state, submitted_s, reason FROM tasks"
               " WHERE task_id NOT IN (SELECT task_id FROM task_history)"
               " ORDER BY queue_position");
  sqlite::exec(db,
               "CREATE INDEX IF NOT EXISTS tasks_by_uav_state"
               " ON tasks (uav_id, state, queue_position)");
  sqlite::exec(db, "CREATE INDEX IF NOT EXISTS history_by_task ON task_history (task_id, id)");
  sqlite::exec(db, "CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
}

// Version 2: a submission rejected at once holds no task id (issue 31: a corrected file
// submitted again under the id was refused as "already known: rejected"). `accepted` tells
// a task queued at submission, which holds its id for good, from one rejected at once,
// which a new submission with its id replaces; the replaced one moves, whole, to
// rejected_submissions. A task of an older file was accepted unless it was rejected and
// never anything else (a task the UAV agent rejected was queued first).
void to_version_2(sqlite3* db) {
  if (!column_exists(db, "tasks", "accepted")) {
    sqlite::exec(db, "ALTER TABLE tasks ADD COLUMN accepted INTEGER NOT NULL DEFAULT 1");
  }
  sqlite::exec(db,
               "UPDATE tasks SET accepted = 0 WHERE state = 'rejected' AND NOT EXISTS"
               " (SELECT 1 FROM task_history h WHERE h.task_id = tasks.task_id"
               " AND h.to_state <> 'rejected')");
  sqlite::exec(db,
               "CREATE TABLE IF NOT EXISTS rejected_submissions ("
               " id INTEGER PRIMARY KEY,"
               " task_id TEXT NOT NULL,"
               " uav_id INTEGER NOT NULL,"
               " queue_position INTEGER NOT NULL,"
               " submitter TEXT NOT NULL,"
               " request_id TEXT NOT NULL,"
               " task_json TEXT NOT NULL,"
               " submitted_s REAL NOT NULL,"
               " reason TEXT NOT NULL)");
  sqlite::exec(db,
               "CREATE INDEX IF NOT EXISTS rejected_by_task ON rejected_submissions (task_id, id)");
}

using Migration = void (*)(sqlite3*);
// kMigrations[i] takes a file from version i to version i + 1. Append, never edit.
const std::vector<Migration> kMigrations = {&to_version_1, &to_version_2};

void write_version(sqlite3* db, int version) {
  sqlite::exec(db, "DELETE FROM schema_version");
  sqlite::Statement insert(db, "INSERT INTO schema_version (version) VALUES (?)");
  insert.bind(1, version).run();
}

void check_not_newer(sqlite3* db, int version, int target) {
  if (version > target) {
    throw StoreError(std::string(sqlite3_db_filename(db, "main")) +
                     ": written by a newer version (schema " + std::to_string(version) +
                     ", this build knows up to " + std::to_string(target) + ")");
  }
}
}  // namespace

int read_version(sqlite3* db) {
  if (!table_exists(db, "schema_version")) return 0;
  sqlite::Statement query(db, "SELECT MAX(version) FROM schema_version");
  return query.step() ? static_cast<int>(query.integer(0)) : 0;
}

void migrate(sqlite3* db, int target) {
  check_not_newer(db, read_version(db), target);
  for (int from = 0; from < target; ++from) {
    sqlite::Transaction transaction(db);
    const int version = read_version(db);
    check_not_newer(db, version, target);
    if (version > from) continue;
    kMigrations.at(static_cast<std::size_t>(from))(db);
    write_version(db, from + 1);
    transaction.commit();
  }
}

}  // namespace cover::task_manager::schema
