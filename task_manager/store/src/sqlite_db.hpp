#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <string>

namespace cover::task_manager::sqlite {

// Throws StoreError "<file>: <what>: <SQLite's message>".
[[noreturn]] void fail(sqlite3* db, const std::string& what);

// Runs SQL that returns no rows (several statements allowed).
void exec(sqlite3* db, const std::string& sql);

// A prepared statement, finalised on destruction. Bind indices start at 1, columns at 0.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int index, const std::string& value);
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, double value);

  // True while a row is available; false when done. Throws on error.
  bool step();
  // Runs a statement that returns no row.
  void run();

  std::string text(int column) const;
  std::int64_t integer(int column) const;
  double real(int column) const;

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE on construction: takes the write lock up front, so a read-then-write
// (e.g. the next queue position) cannot interleave with another writer. Rolls back unless
// commit() was called.
class Transaction {
 public:
  explicit Transaction(sqlite3* db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  sqlite3* db_;
  bool done_ = false;
};

}  // namespace cover::task_manager::sqlite
