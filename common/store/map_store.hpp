#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/store/sqlite_connection.hpp"
#include "common/store/sqlite_statement.hpp"
#include "common/store/store_lock.hpp"
#include "common/store/store_options.hpp"
#include "common/store/store_records.hpp"

namespace fleetmap::store {
namespace internal {
struct WalScan;
}  // namespace internal

// What MapStore::Open found in and beside the file, for the server to say at start.
struct StoreOpenReport {
  bool created = false;        // there was no file: a new, empty store
  int64_t found_version = 0;   // the schema version found (0: new), before any migration
  bool quick_checked = false;  // PRAGMA quick_check ran and passed (Open fails when it does not)
  bool wal_found = false;      // <path>-wal was there before opening: the last writer was killed
  int64_t wal_bytes = 0;       // or is still running
  bool shm_found = false;
  int64_t wal_frames_recovered = 0;  // committed WAL frames SQLite replayed
  // What SQLite's recovery dropped from the WAL (a warning says it): frames written since the WAL
  // was last reset that follow the last transaction it could replay, their bytes (a frame cut
  // short included), and the committed transactions known among them. Those are a lower bound:
  // what a cut-off WAL held past its end cannot be counted, though its -shm, when kept, still
  // counts the frames (wal_committed_frames_lost).
  bool wal_ends_mid_frame = false;
  int64_t wal_frames_dropped = 0;
  int64_t wal_bytes_dropped = 0;
  int64_t wal_commits_dropped = 0;
  int64_t wal_committed_frames_lost = 0;
  bool unclean_close = false;  // the last writer did not close the store (killed, crashed)
  // Data that may have been lost (a missing or damaged WAL), each in one sentence.
  std::vector<std::string> warnings;

  // One line: "created", or the version, check, WAL state and recovery, then the warnings.
  std::string Summary() const;
};

// The fusion server's persistent state in one SQLite file: the latest revision of every tile
// (robot and fused), the history of every revision (the object learner's input) and the robots
// of the fleet. Every write is one transaction, so after a crash the file holds exactly the calls
// that returned OK (see StoreOptions for power loss). Schema: docs/file-formats.md, "Map store".
//
// One connection, not thread-safe: create and call from one thread (the server's fusion worker).
// One MapStore at a time may hold a file: it holds the file's StoreLock while open. Other
// processes may read the file with plain SQLite connections (WAL mode); the lock never blocks them.
class MapStore {
 public:
  // The schema version this code writes, kept in PRAGMA user_version.
  static constexpr int kSchemaVersion = 4;

  // Opens `path`, creating the file and its schema if missing. Fails with a message naming the
  // file when it is empty (0 bytes: truncated, never a store), is not an SQLite database, is
  // corrupt (quick check), holds another application's tables, or has a schema version newer than
  // kSchemaVersion. An older version is migrated. What it found is in open_report().
  // First it takes the file's StoreLock, waiting up to options.lock_timeout_ms for another writer
  // (`on_lock_wait` is told once when it starts waiting); still held, it fails with
  // kInvalidArgument naming the file and the holder's pid, having read nothing.
  static StatusOr<std::unique_ptr<MapStore>> Open(
      const std::string& path, const StoreOptions& options = {},
      const StoreLock::WaitNotice& on_lock_wait = nullptr);
  ~MapStore();
  MapStore(const MapStore&) = delete;
  MapStore& operator=(const MapStore&) = delete;

  // Stores a batch in one transaction: all records or none. Each (owner, tile)'s latest row is
  // replaced when the record is newer (higher revision, or same revision and later stamp); with
  // keep_history, each record not already present (same owner, tile, revision and stamp) is
  // appended to the history, then the oldest rows beyond max_history_rows are dropped. A record
  // that fails ValidateTileRecord refuses the whole batch with kInvalidArgument.
  Status PutTiles(const std::vector<TileRecord>& tiles);

  // Commits a batch in one transaction, all or nothing: first deletes every `removed` key's latest
  // row, history and evidence, then stores `tiles` as PutTiles does and replaces each `evidence`
  // row, and writes `robots` as PutRobot does. An invalid record refuses the whole batch with
  // kInvalidArgument.
  Status Write(const StoreBatch& batch);
  // Every evidence row, ordered by owner, x, y.
  StatusOr<std::vector<EvidenceRecord>> Evidence() const;

  // The latest revision of every tile, or of `owner`'s tiles only; ordered by owner, x, y.
  StatusOr<std::vector<TileRecord>> LatestTiles() const;
  StatusOr<std::vector<TileRecord>> LatestTiles(const TileOwner& owner) const;

  // Every stored revision of `owner`'s `tile` stamped at or after `since_ns`, oldest first.
  StatusOr<std::vector<TileRecord>> TileHistory(const TileOwner& owner, const TileId& tile,
                                                int64_t since_ns = 0) const;

  // Inserts or updates a robot: first_seen_ns keeps the earliest value, last_seen_ns the latest,
  // state and status_payload are replaced.
  Status PutRobot(const RobotRecord& robot);
  // All robots, ordered by id.
  StatusOr<std::vector<RobotRecord>> Robots() const;

  // Removes `owner`'s latest tiles and their history (robot records stay). Unknown owner: OK.
  Status DeleteOwner(const TileOwner& owner);

  StatusOr<int64_t> HistoryRowCount() const;
  // Calls `visit` with every history row, oldest first, one at a time (the history may be larger
  // than memory). Fails only when the store cannot be read.
  Status ForEachHistoryRow(const std::function<void(const TileRecord&)>& visit) const;

  // Appends a finished mapping session; returns its id (ids increase). kInvalidArgument for a
  // record that fails ValidateSessionRecord.
  StatusOr<int64_t> PutSession(const SessionRecord& session);
  // Every stored session, oldest first.
  StatusOr<std::vector<SessionRecord>> Sessions() const;

  // Records an operator's admission (the latest per robot). kInvalidArgument for a robot name
  // that is not valid or a negative time.
  Status PutAdmission(const AdmissionRecord& admission);
  // Every admission, ordered by robot.
  StatusOr<std::vector<AdmissionRecord>> Admissions() const;

  // PRAGMA integrity_check over the whole file: OK, or kDataLoss naming the file.
  Status CheckIntegrity() const;

  const std::string& path() const { return db_->path(); }
  const StoreOpenReport& open_report() const { return report_; }

 private:
  MapStore(std::unique_ptr<StoreLock> lock, std::unique_ptr<SqliteConnection> db,
           const StoreOptions& options);
  Status Initialize();
  // Marks the store open in the main file (not only the WAL), so that the next Open can tell
  // whether this one was closed; says what the last writer left.
  Status CheckLastClose();
  // The file's schema version: 1..kSchemaVersion, or 0 for a new empty file; anything else fails.
  StatusOr<int64_t> ReadSchemaVersion();
  // Creates the schema in a new file (version 0) or migrates an older one, in one transaction.
  Status CreateOrMigrateSchema(int64_t version);
  Status PrepareStatements();
  // The warning for a WAL whose recovery dropped data: what, why, and the newest revision kept.
  std::string DescribeWalLoss(const internal::WalScan& wal) const;
  Status RunCheck(const char* pragma) const;
  Status RunPutRobot(const RobotRecord& robot);
  StatusOr<int64_t> CountHistoryRows() const;
  StatusOr<std::vector<TileRecord>> ReadTiles(SqliteStatement& query) const;

  // Declared first so that it is released last, after the connection has closed.
  std::unique_ptr<StoreLock> lock_;
  // Declared before the statements so that it is destroyed after them.
  std::unique_ptr<SqliteConnection> db_;
  StoreOptions options_;
  // Rows in tile_history, known at open and kept up to date by every committed write, so that
  // trimming to max_history_rows needs no COUNT per batch.
  int64_t history_rows_ = 0;
  StoreOpenReport report_;
  bool marked_open_ = false;  // store_state.open was set by this connection

  std::unique_ptr<SqliteStatement> upsert_latest_;
  std::unique_ptr<SqliteStatement> insert_history_;
  std::unique_ptr<SqliteStatement> trim_history_;
  std::unique_ptr<SqliteStatement> count_history_;
  std::unique_ptr<SqliteStatement> select_latest_all_;
  std::unique_ptr<SqliteStatement> select_latest_owner_;
  std::unique_ptr<SqliteStatement> select_history_;
  std::unique_ptr<SqliteStatement> upsert_robot_;
  std::unique_ptr<SqliteStatement> select_robots_;
  std::unique_ptr<SqliteStatement> insert_session_;
  std::unique_ptr<SqliteStatement> select_sessions_;
  std::unique_ptr<SqliteStatement> upsert_admission_;
  std::unique_ptr<SqliteStatement> select_admissions_;
  std::unique_ptr<SqliteStatement> delete_owner_;
  std::unique_ptr<SqliteStatement> upsert_evidence_;
  std::unique_ptr<SqliteStatement> select_evidence_;
  std::unique_ptr<SqliteStatement> count_tile_history_;
  std::unique_ptr<SqliteStatement> delete_latest_;
  std::unique_ptr<SqliteStatement> delete_evidence_;
  std::unique_ptr<SqliteStatement> select_history_all_;
  std::unique_ptr<SqliteStatement> select_newest_latest_;
};

}  // namespace fleetmap::store
