#include "common/store/sqlite_statement.hpp"

#include <sqlite3.h>

namespace fleetmap::store {

StatusOr<std::unique_ptr<SqliteStatement>> SqliteStatement::Prepare(SqliteConnection& db,
                                                                    const std::string& sql,
                                                                    std::string what) {
  sqlite3_stmt* statement = nullptr;
  const int rc = sqlite3_prepare_v3(db.handle(), sql.c_str(), static_cast<int>(sql.size() + 1),
                                    SQLITE_PREPARE_PERSISTENT, &statement, nullptr);
  if (rc != SQLITE_OK) {
    sqlite3_finalize(statement);
    return db.Error(rc, "preparing the statement for " + what);
  }
  return std::unique_ptr<SqliteStatement>(new SqliteStatement(db, statement, std::move(what)));
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(statement_); }

void SqliteStatement::Reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

Status SqliteStatement::BindResult(int rc, int index) const {
  if (rc == SQLITE_OK) return Status::Ok();
  return db_.Error(rc, what_ + ": binding parameter " + std::to_string(index));
}

Status SqliteStatement::Bind(int index, int64_t value) {
  return BindResult(sqlite3_bind_int64(statement_, index, value), index);
}

Status SqliteStatement::BindText(int index, std::string_view text) {
  // A non-null pointer even for "": SQLite binds NULL for a null pointer.
  const char* data = text.empty() ? "" : text.data();
  return BindResult(
      sqlite3_bind_text64(statement_, index, data, text.size(), SQLITE_TRANSIENT, SQLITE_UTF8),
      index);
}

Status SqliteStatement::BindBlob(int index, std::string_view bytes) {
  const char* data = bytes.empty() ? "" : bytes.data();
  return BindResult(sqlite3_bind_blob64(statement_, index, data, bytes.size(), SQLITE_TRANSIENT),
                    index);
}

StatusOr<bool> SqliteStatement::Step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  // sqlite3_reset returns the step's error again; the message is still the step's.
  const Status status = rc == SQLITE_DONE ? Status::Ok() : db_.Error(rc, what_);
  sqlite3_reset(statement_);
  if (!status.ok()) return status;
  return false;
}

Status SqliteStatement::Run() {
  while (true) {
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, Step());
    if (!row) return Status::Ok();
  }
}

int64_t SqliteStatement::ColumnInt64(int column) const {
  return sqlite3_column_int64(statement_, column);
}

std::string SqliteStatement::ColumnText(int column) const {
  const unsigned char* text = sqlite3_column_text(statement_, column);
  const int size = sqlite3_column_bytes(statement_, column);
  if (text == nullptr) return {};
  return std::string(reinterpret_cast<const char*>(text), static_cast<size_t>(size));
}

std::string SqliteStatement::ColumnBlob(int column) const {
  const void* bytes = sqlite3_column_blob(statement_, column);
  const int size = sqlite3_column_bytes(statement_, column);
  if (bytes == nullptr) return {};  // a zero-length BLOB
  return std::string(static_cast<const char*>(bytes), static_cast<size_t>(size));
}

}  // namespace fleetmap::store
