#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "common/core/status.hpp"
#include "common/store/sqlite_connection.hpp"

struct sqlite3_stmt;

namespace fleetmap::store {

// A prepared SQLite statement, compiled once and reused, finalized on destruction. A run is:
// Reset(), Bind*(), then Step() until it returns false (or Run() for statements without rows).
// Step() resets the statement when it finishes or fails, so an idle statement never pins a read
// snapshot of the WAL. Must be destroyed before its connection. Use from the connection's thread.
class SqliteStatement {
 public:
  // `what` names the statement's purpose in error messages ("upserting a latest tile").
  static StatusOr<std::unique_ptr<SqliteStatement>> Prepare(SqliteConnection& db,
                                                            const std::string& sql,
                                                            std::string what);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  // Ends any previous run and clears the bindings.
  void Reset();

  // Parameters are numbered from 1, as in SQL's ?1, ?2...
  Status Bind(int index, int64_t value);
  Status BindText(int index, std::string_view text);
  // Binds a BLOB; an empty `bytes` is a zero-length BLOB, not NULL.
  Status BindBlob(int index, std::string_view bytes);

  // True when a row is ready for the Column* accessors, false when the statement is done.
  StatusOr<bool> Step();
  // Steps to the end, for statements that return no rows.
  Status Run();

  // Columns of the current row, numbered from 0.
  int64_t ColumnInt64(int column) const;
  std::string ColumnText(int column) const;
  std::string ColumnBlob(int column) const;

 private:
  SqliteStatement(SqliteConnection& db, sqlite3_stmt* statement, std::string what)
      : db_(db), statement_(statement), what_(std::move(what)) {}
  Status BindResult(int rc, int index) const;

  SqliteConnection& db_;
  sqlite3_stmt* statement_ = nullptr;
  std::string what_;
};

}  // namespace fleetmap::store
