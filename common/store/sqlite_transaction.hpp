#pragma once

#include "common/core/status.hpp"
#include "common/store/sqlite_connection.hpp"

namespace fleetmap::store {

// A write transaction: Begin() takes the write lock at once (BEGIN IMMEDIATE), so a busy database
// fails at the start instead of half-way; the destructor rolls back unless Commit() succeeded.
// Scoped to one function on the connection's thread:
//   SqliteTransaction transaction(db);
//   FLEETMAP_RETURN_IF_ERROR(transaction.Begin());
//   ... statements ...
//   FLEETMAP_RETURN_IF_ERROR(transaction.Commit());
class SqliteTransaction {
 public:
  explicit SqliteTransaction(SqliteConnection& db) : db_(db) {}
  ~SqliteTransaction();
  SqliteTransaction(const SqliteTransaction&) = delete;
  SqliteTransaction& operator=(const SqliteTransaction&) = delete;

  Status Begin();
  Status Commit();

 private:
  SqliteConnection& db_;
  bool open_ = false;
};

}  // namespace fleetmap::store
