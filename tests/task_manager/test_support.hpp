#pragma once

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "cover/task_manager/live_view.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::task_manager::testing {

// A fresh directory in the test's scratch folder (removed with it when the test passes,
// kept for a look when it fails): every test runs on real SQLite files.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (cover::test::scratch_dir() / "task_manager_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// One flyable process G0 -> G1, landing.
inline mission::Task make_task(const std::string& id, int uav_id = 0) {
  mission::Task task;
  task.task_id = id;
  task.uav_id = uav_id;
  mission::TransitionProcess p;
  p.from_ugv = 0;
  p.to_ugv = 1;
  p.initial_point_m = {0.5, -0.5, 1.5};
  p.transition_point_m = {0.0, 0.0, 1.2};
  p.final_point_m = {0.0, 0.0, 0.3};
  p.final_action = mission::FinalAction::Land;
  task.processes.push_back(p);
  return task;
}

// Raw SQL on a store's file, as the sqlite3 CLI would do it.
class RawDb {
 public:
  explicit RawDb(const std::string& path) {
    if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK) throw std::runtime_error("open failed");
  }
  ~RawDb() { sqlite3_close(db_); }
  void exec(const std::string& sql) {
    char* error = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string message = error ? error : "?";
      sqlite3_free(error);
      throw std::runtime_error(sql + ": " + message);
    }
  }
  // The first column of the first row, as text ("" when there is none).
  std::string scalar(const std::string& sql) {
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &stmt, nullptr) != SQLITE_OK) {
      throw std::runtime_error(sql + ": " + sqlite3_errmsg(db_));
    }
    std::string value;
    if (sqlite3_step(stmt) == SQLITE_ROW && sqlite3_column_text(stmt, 0)) {
      value = reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0));
    }
    sqlite3_finalize(stmt);
    return value;
  }

 private:
  sqlite3* db_ = nullptr;
};

}  // namespace cover::task_manager::testing
