#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "common/core/status.hpp"

struct sqlite3;

namespace fleetmap::store {

// One open SQLite database connection, closed on destruction. Turns SQLite result codes into
// Status values whose message starts with the database file. Use from one thread.
class SqliteConnection {
 public:
  // Opens (creating if missing) the database at `path` for reading and writing. Opening does not
  // read the file: a file that is not SQLite is only detected by the first statement.
  static StatusOr<std::unique_ptr<SqliteConnection>> Open(const std::string& path);
  ~SqliteConnection();
  SqliteConnection(const SqliteConnection&) = delete;
  SqliteConnection& operator=(const SqliteConnection&) = delete;

  sqlite3* handle() const { return db_; }
  const std::string& path() const { return path_; }

  // Runs SQL that returns no rows we need (PRAGMA settings, DDL, BEGIN/COMMIT). `what` says what
  // the caller was doing, for the error message.
  Status Exec(const char* sql, const std::string& what);

  // Rows inserted, updated or deleted by the last statement (not counting foreign-key cascades).
  int64_t Changes() const;

  // The Status for SQLite result code `rc` returned by a call on this connection while doing
  // `what`: "<path>: corrupt: <sqlite message> (<what>)" for a damaged file,
  // "<path>: not an SQLite database: ..." for a foreign file, "<path>: <what>: <sqlite message>"
  // otherwise.
  Status Error(int rc, const std::string& what) const;

 private:
  SqliteConnection(sqlite3* db, std::string path) : db_(db), path_(std::move(path)) {}

  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace fleetmap::store
