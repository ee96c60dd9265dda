#include "common/store/sqlite_transaction.hpp"

#include <sqlite3.h>

#include "common/core/check.hpp"

namespace fleetmap::store {

SqliteTransaction::~SqliteTransaction() {
  // SQLite may already have rolled back by itself (after SQLITE_FULL, for instance): then the
  // connection is back in autocommit mode and there is nothing to undo.
  if (open_ && sqlite3_get_autocommit(db_.handle()) == 0) {
    sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
  }
}

Status SqliteTransaction::Begin() {
  FLEETMAP_CHECK(!open_, "SqliteTransaction::Begin called twice");
  FLEETMAP_RETURN_IF_ERROR(db_.Exec("BEGIN IMMEDIATE", "beginning a write transaction"));
  open_ = true;
  return Status::Ok();
}

Status SqliteTransaction::Commit() {
  FLEETMAP_CHECK(open_, "SqliteTransaction::Commit without Begin");
  FLEETMAP_RETURN_IF_ERROR(db_.Exec("COMMIT", "committing"));
  open_ = false;
  return Status::Ok();
}

}  // namespace fleetmap::store
