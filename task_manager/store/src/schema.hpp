#pragma once

#include <sqlite3.h>

namespace cover::task_manager::schema {

// The file's schema version: 0 when it has no schema_version table (a new file, or the
// pre-release layout whose tasks table had no `reason` and no history).
int read_version(sqlite3* db);

// Brings the file to `target`, one transaction per migration, each re-reading the version
// under the write lock (another process may be migrating the same file). Throws StoreError
// "written by a newer version" when the file is ahead of `target`.
void migrate(sqlite3* db, int target);

}  // namespace cover::task_manager::schema
