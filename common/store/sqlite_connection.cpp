#include "common/store/sqlite_connection.hpp"

#include <sqlite3.h>

namespace fleetmap::store {
namespace {

StatusCode CodeFor(int rc) {
  switch (rc & 0xff) {
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB:
      return StatusCode::kDataLoss;
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return StatusCode::kUnavailable;
    case SQLITE_FULL:
    case SQLITE_TOOBIG:
    case SQLITE_NOMEM:
      return StatusCode::kResourceExhausted;
    case SQLITE_CANTOPEN:
      return StatusCode::kNotFound;
    case SQLITE_CONSTRAINT:
    case SQLITE_RANGE:
    case SQLITE_MISMATCH:
    case SQLITE_READONLY:
    case SQLITE_PERM:
    case SQLITE_AUTH:
      return StatusCode::kInvalidArgument;
    default:
      return StatusCode::kInternal;
  }
}

}  // namespace

StatusOr<std::unique_ptr<SqliteConnection>> SqliteConnection::Open(const std::string& path) {
  if (path.empty()) return InvalidArgumentError("map store: empty database path");
  sqlite3* db = nullptr;
  // NOMUTEX: each connection is used by one thread (the class contract), so SQLite's own
  // per-connection mutex is not needed.
  const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX;
  const int rc = sqlite3_open_v2(path.c_str(), &db, flags, nullptr);
  std::unique_ptr<SqliteConnection> connection(new SqliteConnection(db, path));
  if (rc != SQLITE_OK) {
    if (db == nullptr) return ResourceExhaustedError(path + ": opening: out of memory");
    return connection->Error(rc, "opening");
  }
  sqlite3_extended_result_codes(db, 1);
  return connection;
}

SqliteConnection::~SqliteConnection() {
  // Every statement is finalized before its connection (MapStore declares them after it), so
  // close succeeds; as the last connection it also checkpoints and removes the WAL file.
  sqlite3_close(db_);
}

Status SqliteConnection::Exec(const char* sql, const std::string& what) {
  const int rc = sqlite3_exec(db_, sql, nullptr, nullptr, nullptr);
  if (rc != SQLITE_OK) return Error(rc, what);
  return Status::Ok();
}

int64_t SqliteConnection::Changes() const { return sqlite3_changes64(db_); }

Status SqliteConnection::Error(int rc, const std::string& what) const {
  const std::string detail = db_ != nullptr ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
  const StatusCode code = CodeFor(rc);
  switch (rc & 0xff) {
    case SQLITE_CORRUPT:
      return Status(code, path_ + ": corrupt: " + detail + " (" + what + ")");
    case SQLITE_NOTADB:
      return Status(code, path_ + ": not an SQLite database: " + detail + " (" + what + ")");
    default:
      return Status(code, path_ + ": " + what + ": " + detail);
  }
}

}  // namespace fleetmap::store
