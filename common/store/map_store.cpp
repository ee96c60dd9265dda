#include "common/store/map_store.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "common/store/internal/wal_scan.hpp"
#include "common/store/sqlite_transaction.hpp"

namespace fleetmap::store {
namespace {

// Schema version 1, then the migrations to each later version. Documented in docs/file-formats.md,
// "Map store (SQLite)": change both together, and bump MapStore::kSchemaVersion with a migration.
constexpr char kCreateSchemaV1[] = R"sql(
CREATE TABLE tile_latest (
  owner    TEXT    NOT NULL,
  tile_x   INTEGER NOT NULL,
  tile_y   INTEGER NOT NULL,
  revision INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  payload  BLOB    NOT NULL,
  PRIMARY KEY (owner, tile_x, tile_y)
);
CREATE TABLE tile_history (
  id       INTEGER PRIMARY KEY,
  owner    TEXT    NOT NULL,
  tile_x   INTEGER NOT NULL,
  tile_y   INTEGER NOT NULL,
  revision INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  payload  BLOB    NOT NULL,
  UNIQUE (owner, tile_x, tile_y, stamp_ns, revision),
  FOREIGN KEY (owner, tile_x, tile_y) REFERENCES tile_latest (owner, tile_x, tile_y)
    ON DELETE CASCADE
);
CREATE TABLE robots (
  robot          TEXT    NOT NULL PRIMARY KEY,
  first_seen_ns  INTEGER NOT NULL,
  last_seen_ns   INTEGER NOT NULL,
  state          TEXT    NOT NULL CHECK (state IN ('active', 'left', 'lost')),
  status_payload BLOB    NOT NULL
);
PRAGMA user_version = 1;
)sql";

// Version 2: finished mapping sessions, the object learner's input.
constexpr char kMigrateToV2[] = R"sql(
CREATE TABLE sessions (
  id         INTEGER PRIMARY KEY,
  robot      TEXT    NOT NULL,
  started_ns INTEGER NOT NULL,
  ended_ns   INTEGER NOT NULL,
  payload    BLOB    NOT NULL
);
PRAGMA user_version = 2;
)sql";

// Version 3: each robot's evidence per tile, so that the fused map is rebuilt exactly, and whether
// the last writer closed the store.
constexpr char kMigrateToV3[] = R"sql(
CREATE TABLE tile_evidence (
  owner    TEXT    NOT NULL,
  tile_x   INTEGER NOT NULL,
  tile_y   INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  payload  BLOB    NOT NULL,
  PRIMARY KEY (owner, tile_x, tile_y)
);
CREATE TABLE store_state (
  name  TEXT    NOT NULL PRIMARY KEY,
  value INTEGER NOT NULL
);
INSERT INTO store_state (name, value) VALUES ('open', 0), ('opened_ns', 0);
PRAGMA user_version = 3;
)sql";

// Version 4: the robots an operator admitted, so that an admission outlives a restart.
constexpr char kMigrateToV4[] = R"sql(
CREATE TABLE admissions (
  robot       TEXT    NOT NULL PRIMARY KEY,
  operator    TEXT    NOT NULL,
  admitted_ns INTEGER NOT NULL
);
PRAGMA user_version = 4;
)sql";

// Upsert, never INSERT OR REPLACE: REPLACE deletes the old row, and the delete would cascade to
// the tile's history.
constexpr char kUpsertLatest[] = R"sql(
INSERT INTO tile_latest (owner, tile_x, tile_y, revision, stamp_ns, payload)
VALUES (?1, ?2, ?3, ?4, ?5, ?6)
ON CONFLICT (owner, tile_x, tile_y) DO UPDATE SET
  revision = excluded.revision, stamp_ns = excluded.stamp_ns, payload = excluded.payload
WHERE (excluded.revision, excluded.stamp_ns) > (tile_latest.revision, tile_latest.stamp_ns)
)sql";

// A sample delivered twice (DDS re-sends transient-local tiles after a restart) is stored once.
constexpr char kInsertHistory[] = R"sql(
INSERT INTO tile_history (owner, tile_x, tile_y, revision, stamp_ns, payload)
VALUES (?1, ?2, ?3, ?4, ?5, ?6)
ON CONFLICT DO NOTHING
)sql";

constexpr char kTrimHistory[] = R"sql(
DELETE FROM tile_history WHERE id IN (SELECT id FROM tile_history ORDER BY id LIMIT ?1)
)sql";

constexpr char kCountHistory[] = "SELECT count(*) FROM tile_history";

constexpr char kSelectLatestAll[] = R"sql(
SELECT owner, tile_x, tile_y, revision, stamp_ns, payload FROM tile_latest
ORDER BY owner, tile_x, tile_y
)sql";

constexpr char kSelectLatestOwner[] = R"sql(
SELECT owner, tile_x, tile_y, revision, stamp_ns, payload FROM tile_latest
WHERE owner = ?1 ORDER BY tile_x, tile_y
)sql";

constexpr char kSelectHistory[] = R"sql(
SELECT owner, tile_x, tile_y, revision, stamp_ns, payload FROM tile_history
WHERE owner = ?1 AND tile_x = ?2 AND tile_y = ?3 AND stamp_ns >= ?4
ORDER BY stamp_ns, revision
)sql";

constexpr char kUpsertRobot[] = R"sql(
INSERT INTO robots (robot, first_seen_ns, last_seen_ns, state, status_payload)
VALUES (?1, ?2, ?3, ?4, ?5)
ON CONFLICT (robot) DO UPDATE SET
  first_seen_ns = min(first_seen_ns, excluded.first_seen_ns),
  last_seen_ns = max(last_seen_ns, excluded.last_seen_ns),
  state = excluded.state,
  status_payload = excluded.status_payload
)sql";

constexpr char kSelectRobots[] = R"sql(
SELECT robot, first_seen_ns, last_seen_ns, state, status_payload FROM robots ORDER BY robot
)sql";

constexpr char kInsertSession[] = R"sql(
INSERT INTO sessions (robot, started_ns, ended_ns, payload) VALUES (?1, ?2, ?3, ?4)
)sql";

constexpr char kSelectSessions[] = R"sql(
SELECT id, robot, started_ns, ended_ns, payload FROM sessions ORDER BY id
)sql";

constexpr char kUpsertAdmission[] = R"sql(
INSERT INTO admissions (robot, operator, admitted_ns) VALUES (?1, ?2, ?3)
ON CONFLICT (robot) DO UPDATE SET operator = excluded.operator, admitted_ns = excluded.admitted_ns
)sql";

constexpr char kSelectAdmissions[] = R"sql(
SELECT robot, operator, admitted_ns FROM admissions ORDER BY robot
)sql";

// The tile's history goes with it (ON DELETE CASCADE).
constexpr char kDeleteOwner[] = "DELETE FROM tile_latest WHERE owner = ?1";

// The server writes its current evidence: always replace.
constexpr char kUpsertEvidence[] = R"sql(
INSERT INTO tile_evidence (owner, tile_x, tile_y, stamp_ns, payload) VALUES (?1, ?2, ?3, ?4, ?5)
ON CONFLICT (owner, tile_x, tile_y) DO UPDATE SET
  stamp_ns = excluded.stamp_ns, payload = excluded.payload
)sql";

constexpr char kSelectEvidence[] = R"sql(
SELECT owner, tile_x, tile_y, stamp_ns, payload FROM tile_evidence ORDER BY owner, tile_x, tile_y
)sql";

// Through the UNIQUE index: cascaded deletes are not in Changes(), so count them first.
constexpr char kCountTileHistory[] = R"sql(
SELECT count(*) FROM tile_history WHERE owner = ?1 AND tile_x = ?2 AND tile_y = ?3
)sql";

constexpr char kSelectHistoryAll[] = R"sql(
SELECT owner, tile_x, tile_y, revision, stamp_ns, payload FROM tile_history ORDER BY id
)sql";

// The newest revision the store holds, to say from when on a damaged WAL lost what it held.
constexpr char kSelectNewestLatest[] = R"sql(
SELECT owner, tile_x, tile_y, revision, stamp_ns FROM tile_latest ORDER BY stamp_ns DESC LIMIT 1
)sql";

constexpr char kDeleteLatest[] =
    "DELETE FROM tile_latest WHERE owner = ?1 AND tile_x = ?2 AND tile_y = ?3";
constexpr char kDeleteEvidence[] =
    "DELETE FROM tile_evidence WHERE owner = ?1 AND tile_x = ?2 AND tile_y = ?3";

// At most this many problems from a failed check are quoted in the error message.
constexpr int kMaxCheckMessages = 3;

// The single integer a query such as "PRAGMA user_version" returns.
StatusOr<int64_t> QueryInt(SqliteConnection& db, const char* sql, const std::string& what) {
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<SqliteStatement> query,
                            SqliteStatement::Prepare(db, sql, what));
  FLEETMAP_ASSIGN_OR_RETURN(const bool row, query->Step());
  if (!row) return InternalError(db.path() + ": " + what + ": no result row");
  const int64_t value = query->ColumnInt64(0);
  query->Reset();
  return value;
}

Status BindTile(SqliteStatement& statement, const TileRecord& tile) {
  statement.Reset();
  FLEETMAP_RETURN_IF_ERROR(statement.BindText(1, tile.owner.key()));
  FLEETMAP_RETURN_IF_ERROR(statement.Bind(2, tile.tile.x));
  FLEETMAP_RETURN_IF_ERROR(statement.Bind(3, tile.tile.y));
  FLEETMAP_RETURN_IF_ERROR(statement.Bind(4, tile.revision));
  FLEETMAP_RETURN_IF_ERROR(statement.Bind(5, tile.stamp_ns));
  return statement.BindBlob(6, tile.payload);
}

}  // namespace

MapStore::MapStore(std::unique_ptr<StoreLock> lock, std::unique_ptr<SqliteConnection> db,
                   const StoreOptions& options)
    : lock_(std::move(lock)), db_(std::move(db)), options_(options) {}

// Statements are members declared after db_, so they are finalized before the connection closes.
MapStore::~MapStore() {
  // A clean close: the next Open will not warn. Failing (full disk) only makes it warn.
  // Only a store this process marked open: a refused file is never written.
  if (db_ != nullptr && marked_open_) {
    (void)db_->Exec("UPDATE store_state SET value = 0 WHERE name = 'open'", "marking closed");
  }
}

std::string StoreOpenReport::Summary() const {
  std::string out;
  if (created) {
    out = "created a new store";
  } else {
    out = "schema version " + std::to_string(found_version);
    out += quick_checked ? ", quick check ok" : ", quick check skipped";
    if (unclean_close) {
      out += ", not closed by its last writer";
      out += wal_found ? " (WAL of " + std::to_string(wal_bytes) + " bytes, " +
                             std::to_string(wal_frames_recovered) + " frames recovered"
                       : " (no WAL";
      out += shm_found ? ", -shm present)" : ", no -shm)";
    } else {
      out += ", closed cleanly";
    }
  }
  for (const std::string& warning : warnings) out += "; WARNING: " + warning;
  return out;
}

StatusOr<std::unique_ptr<MapStore>> MapStore::Open(const std::string& path,
                                                   const StoreOptions& options,
                                                   const StoreLock::WaitNotice& on_lock_wait) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate().WithContext(path));
  // One writer: nothing is read (the WAL scan included) while another may be writing.
  std::unique_ptr<StoreLock> lock;
  if (!path.empty() && path != ":memory:") {
    FLEETMAP_ASSIGN_OR_RETURN(
        lock,
        StoreLock::Acquire(path, std::chrono::milliseconds(options.lock_timeout_ms), on_lock_wait));
  }
  // What lies on disk before SQLite touches it: opening replays, and writing resets, the WAL.
  std::error_code error;
  const bool exists = !path.empty() && std::filesystem::exists(path, error);
  const internal::WalScan wal = path.empty() ? internal::WalScan{} : internal::ScanWal(path);
  if (exists && std::filesystem::is_regular_file(path, error) &&
      std::filesystem::file_size(path, error) == 0) {
    std::string message = path +
                          ": the file is empty (0 bytes): a map store never is, so it was "
                          "truncated, or it is not a map store";
    if (wal.found) {
      message += " (" + path + "-wal beside it holds " + std::to_string(wal.bytes) + " bytes)";
    }
    return DataLossError(message +
                         ". To start a new map, delete it with its -wal and -shm files, or pass "
                         "a path that does not exist; to keep the old map, restore the file "
                         "from a backup");
  }
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<SqliteConnection> db, SqliteConnection::Open(path));
  std::unique_ptr<MapStore> store(new MapStore(std::move(lock), std::move(db), options));
  StoreOpenReport& report = store->report_;
  report.created = !exists;
  report.wal_found = wal.found;
  report.wal_bytes = wal.bytes;
  report.shm_found = std::filesystem::exists(path + "-shm", error);
  FLEETMAP_RETURN_IF_ERROR(store->Initialize());
  if (wal.found && wal.bytes > 32 && !wal.header_valid) {
    report.warnings.push_back(
        path + "-wal (" + std::to_string(wal.bytes) +
        " bytes) has no valid header: SQLite ignored it, and what it held is lost");
  }
  if (wal.DropsData()) {
    report.wal_ends_mid_frame = wal.EndsMidFrame();
    report.wal_frames_dropped = wal.dropped_frames + (wal.EndsMidFrame() ? 1 : 0);
    report.wal_bytes_dropped = wal.DroppedBytes();
    report.wal_committed_frames_lost = wal.CommittedFramesLost();
    // A cut that leaves no commit frame behind still lost the one its -shm counts.
    report.wal_commits_dropped =
        std::max<int64_t>(wal.dropped_commits, wal.CommittedFramesLost() > 0 ? 1 : 0);
    report.warnings.push_back(store->DescribeWalLoss(wal));
  }
  return store;
}

std::string MapStore::DescribeWalLoss(const internal::WalScan& wal) const {
  const auto frames = [](int64_t first, int64_t last) {
    return first == last ? "frame " + std::to_string(first)
                         : "frames " + std::to_string(first) + "-" + std::to_string(last);
  };
  const std::string frames_kept =
      wal.kept_frames > 0 ? " (" + frames(1, wal.kept_frames) + ")" : "";
  std::string out = path() + "-wal is damaged: recovery replayed " +
                    std::to_string(wal.kept_commits) + " transactions" + frames_kept +
                    " and dropped " + std::to_string(report_.wal_frames_dropped) + " frames (" +
                    std::to_string(report_.wal_bytes_dropped) + " bytes) after them: ";
  std::vector<std::string> causes;
  const int64_t read_on = wal.stop_frame > 0 ? wal.stop_frame - 1 : wal.whole_frames;
  if (read_on > wal.kept_frames) {
    causes.push_back(frames(wal.kept_frames + 1, read_on) +
                     " belong to a transaction without its commit frame");
  }
  if (wal.stop == internal::WalScan::Stop::kDamagedFrame) {
    causes.push_back("frame " + std::to_string(wal.stop_frame) +
                     " fails its checksum, so nothing after it is read");
  }
  if (wal.EndsMidFrame()) {
    causes.push_back("the file ends mid-frame (frame " + std::to_string(wal.whole_frames + 1) +
                     " has " + std::to_string(wal.partial_bytes) + " of " +
                     std::to_string(wal.frame_bytes) +
                     " bytes: the file was cut, or its writer was killed while writing it)");
  }
  if (wal.dropped_commits > 0) {
    causes.push_back(std::to_string(wal.dropped_commits) +
                     " committed transactions among the dropped frames are lost");
  }
  if (wal.CommittedFramesLost() > 0) {
    causes.push_back("its last writer's -shm counts " +
                     std::to_string(wal.writer_committed_frames) + " committed frames, so " +
                     std::to_string(wal.CommittedFramesLost()) +
                     " committed frames (at least one transaction) are lost");
  }
  for (size_t i = 0; i < causes.size(); ++i) out += (i > 0 ? "; " : "") + causes[i];
  // From when on the map is missing: later revisions come back only if their robots re-send them.
  if (select_newest_latest_ == nullptr) return out;
  select_newest_latest_->Reset();
  const StatusOr<bool> row = select_newest_latest_->Step();
  if (row.ok() && *row) {
    const int64_t stamp_ns = select_newest_latest_->ColumnInt64(4);
    const std::time_t seconds = static_cast<std::time_t>(stamp_ns / 1'000'000'000);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    std::array<char, 32> date{};
    std::strftime(date.data(), date.size(), "%Y-%m-%dT%H:%M:%SZ", &utc);
    out += ". The newest revision kept is " + select_newest_latest_->ColumnText(0) + "'s tile (" +
           std::to_string(select_newest_latest_->ColumnInt64(1)) + ", " +
           std::to_string(select_newest_latest_->ColumnInt64(2)) + ") revision " +
           std::to_string(select_newest_latest_->ColumnInt64(3)) + " of " + date.data() +
           ": what was stored after it is lost unless robots send it again";
  } else {
    out += ". The store holds no tile: everything the WAL held is lost";
  }
  select_newest_latest_->Reset();
  return out;
}

Status MapStore::Initialize() {
  sqlite3_busy_timeout(db_->handle(), options_.busy_timeout_ms);
  // The first statement reads the file: a foreign, damaged or too new file fails here, before
  // anything is written to it.
  FLEETMAP_ASSIGN_OR_RETURN(const int64_t version, ReadSchemaVersion());
  report_.found_version = version;
  if (options_.verify_on_open) {
    FLEETMAP_RETURN_IF_ERROR(RunCheck("PRAGMA quick_check"));
    report_.quick_checked = true;
  }

  FLEETMAP_ASSIGN_OR_RETURN(
      std::unique_ptr<SqliteStatement> wal,
      SqliteStatement::Prepare(*db_, "PRAGMA journal_mode = WAL", "switching to WAL mode"));
  FLEETMAP_ASSIGN_OR_RETURN(const bool row, wal->Step());
  const std::string mode = row ? wal->ColumnText(0) : "";
  wal->Reset();
  if (mode != "wal") {
    return UnavailableError(path() + ": switching to WAL mode: the journal mode stayed '" + mode +
                            "' (WAL needs a local file system with shared memory)");
  }
  FLEETMAP_RETURN_IF_ERROR(db_->Exec(
      options_.synchronous_full ? "PRAGMA synchronous = FULL" : "PRAGMA synchronous = NORMAL",
      "setting the synchronous mode"));
  FLEETMAP_RETURN_IF_ERROR(db_->Exec("PRAGMA foreign_keys = ON", "enabling foreign keys"));
  if (options_.max_page_count > 0) {
    const std::string cap = "PRAGMA max_page_count = " + std::to_string(options_.max_page_count);
    FLEETMAP_RETURN_IF_ERROR(db_->Exec(cap.c_str(), "capping the file size"));
  }
  // Folds whatever the WAL held into the main file; its frame count is what SQLite recovered.
  // (A new file has no WAL yet: SQLite refuses to checkpoint it.) PASSIVE, because TRUNCATE
  // reports the emptied WAL; CheckLastClose() truncates it.
  if (!report_.created) {
    FLEETMAP_ASSIGN_OR_RETURN(
        std::unique_ptr<SqliteStatement> checkpoint,
        SqliteStatement::Prepare(*db_, "PRAGMA wal_checkpoint(PASSIVE)", "checkpointing the WAL"));
    FLEETMAP_ASSIGN_OR_RETURN(const bool checkpointed, checkpoint->Step());
    if (checkpointed)
      report_.wal_frames_recovered = std::max<int64_t>(0, checkpoint->ColumnInt64(1));
    checkpoint->Reset();
  }

  FLEETMAP_RETURN_IF_ERROR(CreateOrMigrateSchema(version));
  FLEETMAP_RETURN_IF_ERROR(CheckLastClose());

  FLEETMAP_RETURN_IF_ERROR(PrepareStatements());
  FLEETMAP_ASSIGN_OR_RETURN(history_rows_, CountHistoryRows());
  return Status::Ok();
}

StatusOr<int64_t> MapStore::ReadSchemaVersion() {
  FLEETMAP_ASSIGN_OR_RETURN(const int64_t version,
                            QueryInt(*db_, "PRAGMA user_version", "reading the schema version"));
  if (version > kSchemaVersion) {
    return InvalidArgumentError(path() + ": schema version " + std::to_string(version) +
                                " is newer than this fleetmap supports (" +
                                std::to_string(kSchemaVersion) +
                                "); open it with a newer fleetmap");
  }
  if (version >= 1) return version;  // current, or older and migrated by Initialize()
  if (version < 0) {
    return InvalidArgumentError(path() + ": schema version " + std::to_string(version) +
                                " is not a fleetmap map store version");
  }
  // Version 0: a new file, or another application's database.
  FLEETMAP_ASSIGN_OR_RETURN(
      const int64_t objects,
      QueryInt(*db_, "SELECT count(*) FROM sqlite_master", "reading the schema"));
  if (objects > 0) {
    return InvalidArgumentError(path() + ": not a fleetmap map store: it has " +
                                std::to_string(objects) +
                                " tables or indexes but no fleetmap schema version");
  }
  return version;
}

Status MapStore::CreateOrMigrateSchema(int64_t version) {
  if (version == kSchemaVersion) return Status::Ok();
  // One transaction: a crash mid-way leaves the file at its old version, whole.
  SqliteTransaction transaction(*db_);
  FLEETMAP_RETURN_IF_ERROR(transaction.Begin());
  if (version < 1) FLEETMAP_RETURN_IF_ERROR(db_->Exec(kCreateSchemaV1, "creating the schema"));
  if (version < 2) {
    FLEETMAP_RETURN_IF_ERROR(db_->Exec(kMigrateToV2, "migrating the schema to version 2"));
  }
  if (version < 3) {
    FLEETMAP_RETURN_IF_ERROR(db_->Exec(kMigrateToV3, "migrating the schema to version 3"));
  }
  if (version < 4) {
    FLEETMAP_RETURN_IF_ERROR(db_->Exec(kMigrateToV4, "migrating the schema to version 4"));
  }
  return transaction.Commit();
}

Status MapStore::CheckLastClose() {
  FLEETMAP_ASSIGN_OR_RETURN(const int64_t open,
                            QueryInt(*db_, "SELECT value FROM store_state WHERE name = 'open'",
                                     "reading the store state"));
  report_.unclean_close = open != 0;
  if (report_.unclean_close && !report_.wal_found) {
    FLEETMAP_ASSIGN_OR_RETURN(
        const int64_t opened_ns,
        QueryInt(*db_, "SELECT value FROM store_state WHERE name = 'opened_ns'",
                 "reading the store state"));
    report_.warnings.push_back(
        path() + " was not closed by the server that opened it (at " +
        std::to_string(opened_ns / 1'000'000'000) + " s since the epoch) and its write-ahead log " +
        path() +
        "-wal is missing: what that server committed after opening may be lost (keep the -wal "
        "file with the store when copying or moving it)");
  }
  const int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::system_clock::now().time_since_epoch())
                             .count();
  const std::string mark =
      "BEGIN IMMEDIATE; UPDATE store_state SET value = 1 WHERE name = 'open'; "
      "UPDATE store_state SET value = " +
      std::to_string(now_ns) + " WHERE name = 'opened_ns'; COMMIT;";
  if (const Status marked = db_->Exec(mark.c_str(), "marking the store open"); !marked.ok()) {
    (void)db_->Exec("ROLLBACK", "marking the store open");
    report_.warnings.push_back(std::string(marked.message()) +
                               " (an unclean close will not be detected)");
    return Status::Ok();
  }
  marked_open_ = true;
  // In the main file, not only in the WAL: a lost WAL must not take the mark with it.
  if (const Status checkpointed = db_->Exec("PRAGMA wal_checkpoint(TRUNCATE)", "checkpointing");
      !checkpointed.ok()) {
    report_.warnings.push_back(std::string(checkpointed.message()) +
                               " (a lost WAL would take the open mark with it)");
  }
  return Status::Ok();
}

Status MapStore::RunCheck(const char* pragma) const {
  FLEETMAP_ASSIGN_OR_RETURN(std::unique_ptr<SqliteStatement> check,
                            SqliteStatement::Prepare(*db_, pragma, "checking integrity"));
  // One row per problem, or one row holding several lines, depending on the check.
  std::string problems;
  int count = 0;
  while (true) {
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, check->Step());
    if (!row) break;
    std::istringstream lines(check->ColumnText(0));
    std::string line;
    while (std::getline(lines, line)) {
      if (line.empty() || line == "ok" || line.rfind("*** in database", 0) == 0) continue;
      if (count < kMaxCheckMessages) problems += (count > 0 ? "; " : "") + line;
      ++count;
    }
  }
  if (count == 0) return Status::Ok();
  if (count > kMaxCheckMessages) {
    problems += "; and " + std::to_string(count - kMaxCheckMessages) + " more problems";
  }
  return DataLossError(path() + ": corrupt: " + problems + " (" + pragma + ")");
}

Status MapStore::PrepareStatements() {
  const auto prepare = [this](std::unique_ptr<SqliteStatement>* out, const char* sql,
                              const char* what) -> Status {
    FLEETMAP_ASSIGN_OR_RETURN(*out, SqliteStatement::Prepare(*db_, sql, what));
    return Status::Ok();
  };
  FLEETMAP_RETURN_IF_ERROR(prepare(&upsert_latest_, kUpsertLatest, "writing a latest tile"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&insert_history_, kInsertHistory, "appending tile history"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&trim_history_, kTrimHistory, "trimming tile history"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&count_history_, kCountHistory, "counting history rows"));
  FLEETMAP_RETURN_IF_ERROR(
      prepare(&select_latest_all_, kSelectLatestAll, "reading the latest tiles"));
  FLEETMAP_RETURN_IF_ERROR(
      prepare(&select_latest_owner_, kSelectLatestOwner, "reading an owner's latest tiles"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&select_history_, kSelectHistory, "reading tile history"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&upsert_robot_, kUpsertRobot, "writing a robot"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&select_robots_, kSelectRobots, "reading the robots"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&insert_session_, kInsertSession, "writing a session"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&select_sessions_, kSelectSessions, "reading the sessions"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&upsert_admission_, kUpsertAdmission, "writing an admission"));
  FLEETMAP_RETURN_IF_ERROR(
      prepare(&select_admissions_, kSelectAdmissions, "reading the admissions"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&upsert_evidence_, kUpsertEvidence, "writing tile evidence"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&select_evidence_, kSelectEvidence, "reading tile evidence"));
  FLEETMAP_RETURN_IF_ERROR(
      prepare(&count_tile_history_, kCountTileHistory, "counting a tile's history"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&delete_latest_, kDeleteLatest, "deleting a tile"));
  FLEETMAP_RETURN_IF_ERROR(
      prepare(&select_history_all_, kSelectHistoryAll, "reading the whole tile history"));
  FLEETMAP_RETURN_IF_ERROR(
      prepare(&select_newest_latest_, kSelectNewestLatest, "reading the newest tile"));
  FLEETMAP_RETURN_IF_ERROR(prepare(&delete_evidence_, kDeleteEvidence, "deleting tile evidence"));
  return prepare(&delete_owner_, kDeleteOwner, "deleting an owner's tiles");
}

StatusOr<int64_t> MapStore::CountHistoryRows() const {
  count_history_->Reset();
  FLEETMAP_ASSIGN_OR_RETURN(const bool row, count_history_->Step());
  if (!row) return InternalError(path() + ": counting history rows: no result row");
  const int64_t count = count_history_->ColumnInt64(0);
  count_history_->Reset();
  return count;
}

Status MapStore::PutTiles(const std::vector<TileRecord>& tiles) {
  StoreBatch batch;
  batch.tiles = tiles;
  return Write(batch);
}

Status MapStore::Write(const StoreBatch& batch) {
  const std::string name = "batch of " + std::to_string(batch.tiles.size()) + " tiles";
  for (size_t i = 0; i < batch.tiles.size(); ++i) {
    const Status valid = ValidateTileRecord(batch.tiles[i]);
    if (!valid.ok())
      return valid.WithContext(path() + ": " + name + ", record " + std::to_string(i));
  }
  for (size_t i = 0; i < batch.evidence.size(); ++i) {
    const Status valid = ValidateEvidenceRecord(batch.evidence[i]);
    if (!valid.ok()) return valid.WithContext(path() + ": evidence record " + std::to_string(i));
  }
  for (const RobotRecord& robot : batch.robots) {
    FLEETMAP_RETURN_IF_ERROR(ValidateRobotRecord(robot).WithContext(path()));
  }
  if (batch.empty()) return Status::Ok();

  SqliteTransaction transaction(*db_);
  FLEETMAP_RETURN_IF_ERROR(transaction.Begin());
  int64_t history_rows = history_rows_;
  const auto bind_key = [](SqliteStatement& statement, const std::string& owner,
                           const TileId& tile) -> Status {
    statement.Reset();
    FLEETMAP_RETURN_IF_ERROR(statement.BindText(1, owner));
    FLEETMAP_RETURN_IF_ERROR(statement.Bind(2, tile.x));
    return statement.Bind(3, tile.y);
  };
  for (const TileKey& key : batch.removed) {
    FLEETMAP_RETURN_IF_ERROR(bind_key(*count_tile_history_, key.owner.key(), key.tile));
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, count_tile_history_->Step());
    const int64_t tile_history = row ? count_tile_history_->ColumnInt64(0) : 0;
    count_tile_history_->Reset();
    FLEETMAP_RETURN_IF_ERROR(bind_key(*delete_latest_, key.owner.key(), key.tile));
    FLEETMAP_RETURN_IF_ERROR(delete_latest_->Run());
    if (db_->Changes() > 0) history_rows -= tile_history;  // the cascade took its history
    FLEETMAP_RETURN_IF_ERROR(bind_key(*delete_evidence_, key.owner.key(), key.tile));
    FLEETMAP_RETURN_IF_ERROR(delete_evidence_->Run());
  }
  for (const TileRecord& tile : batch.tiles) {
    FLEETMAP_RETURN_IF_ERROR(BindTile(*upsert_latest_, tile));
    FLEETMAP_RETURN_IF_ERROR(upsert_latest_->Run());
    if (options_.keep_history) {
      FLEETMAP_RETURN_IF_ERROR(BindTile(*insert_history_, tile));
      FLEETMAP_RETURN_IF_ERROR(insert_history_->Run());
      history_rows += db_->Changes();
    }
  }
  for (const EvidenceRecord& evidence : batch.evidence) {
    FLEETMAP_RETURN_IF_ERROR(bind_key(*upsert_evidence_, evidence.robot.value, evidence.tile));
    FLEETMAP_RETURN_IF_ERROR(upsert_evidence_->Bind(4, evidence.stamp_ns));
    FLEETMAP_RETURN_IF_ERROR(upsert_evidence_->BindBlob(5, evidence.payload));
    FLEETMAP_RETURN_IF_ERROR(upsert_evidence_->Run());
  }
  for (const RobotRecord& robot : batch.robots) FLEETMAP_RETURN_IF_ERROR(RunPutRobot(robot));
  if (options_.max_history_rows > 0 && history_rows > options_.max_history_rows) {
    trim_history_->Reset();
    FLEETMAP_RETURN_IF_ERROR(trim_history_->Bind(1, history_rows - options_.max_history_rows));
    FLEETMAP_RETURN_IF_ERROR(trim_history_->Run());
    history_rows -= db_->Changes();
  }
  FLEETMAP_RETURN_IF_ERROR(transaction.Commit());
  history_rows_ = history_rows;
  return Status::Ok();
}

StatusOr<std::vector<EvidenceRecord>> MapStore::Evidence() const {
  select_evidence_->Reset();
  std::vector<EvidenceRecord> out;
  while (true) {
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, select_evidence_->Step());
    if (!row) break;
    EvidenceRecord& evidence = out.emplace_back();
    evidence.robot = RobotId{select_evidence_->ColumnText(0)};
    evidence.tile.x = static_cast<int32_t>(select_evidence_->ColumnInt64(1));
    evidence.tile.y = static_cast<int32_t>(select_evidence_->ColumnInt64(2));
    evidence.stamp_ns = select_evidence_->ColumnInt64(3);
    evidence.payload = select_evidence_->ColumnBlob(4);
  }
  return out;
}

StatusOr<std::vector<TileRecord>> MapStore::ReadTiles(SqliteStatement& query) const {
  std::vector<TileRecord> tiles;
  while (true) {
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, query.Step());
    if (!row) break;
    TileRecord& tile = tiles.emplace_back();
    tile.owner = TileOwner::FromKey(query.ColumnText(0));
    tile.tile.x = static_cast<int32_t>(query.ColumnInt64(1));
    tile.tile.y = static_cast<int32_t>(query.ColumnInt64(2));
    tile.revision = static_cast<uint32_t>(query.ColumnInt64(3));
    tile.stamp_ns = query.ColumnInt64(4);
    tile.payload = query.ColumnBlob(5);
  }
  return tiles;
}

StatusOr<std::vector<TileRecord>> MapStore::LatestTiles() const {
  select_latest_all_->Reset();
  return ReadTiles(*select_latest_all_);
}

StatusOr<std::vector<TileRecord>> MapStore::LatestTiles(const TileOwner& owner) const {
  select_latest_owner_->Reset();
  FLEETMAP_RETURN_IF_ERROR(select_latest_owner_->BindText(1, owner.key()));
  return ReadTiles(*select_latest_owner_);
}

StatusOr<std::vector<TileRecord>> MapStore::TileHistory(const TileOwner& owner, const TileId& tile,
                                                        int64_t since_ns) const {
  select_history_->Reset();
  FLEETMAP_RETURN_IF_ERROR(select_history_->BindText(1, owner.key()));
  FLEETMAP_RETURN_IF_ERROR(select_history_->Bind(2, tile.x));
  FLEETMAP_RETURN_IF_ERROR(select_history_->Bind(3, tile.y));
  FLEETMAP_RETURN_IF_ERROR(select_history_->Bind(4, since_ns));
  return ReadTiles(*select_history_);
}

Status MapStore::PutRobot(const RobotRecord& robot) {
  FLEETMAP_RETURN_IF_ERROR(ValidateRobotRecord(robot).WithContext(path()));
  // A single statement is its own transaction.
  return RunPutRobot(robot);
}

Status MapStore::RunPutRobot(const RobotRecord& robot) {
  upsert_robot_->Reset();
  FLEETMAP_RETURN_IF_ERROR(upsert_robot_->BindText(1, robot.robot.value));
  FLEETMAP_RETURN_IF_ERROR(upsert_robot_->Bind(2, robot.first_seen_ns));
  FLEETMAP_RETURN_IF_ERROR(upsert_robot_->Bind(3, robot.last_seen_ns));
  FLEETMAP_RETURN_IF_ERROR(upsert_robot_->BindText(4, robot.state));
  FLEETMAP_RETURN_IF_ERROR(upsert_robot_->BindBlob(5, robot.status_payload));
  return upsert_robot_->Run();
}

StatusOr<std::vector<RobotRecord>> MapStore::Robots() const {
  select_robots_->Reset();
  std::vector<RobotRecord> robots;
  while (true) {
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, select_robots_->Step());
    if (!row) break;
    RobotRecord& robot = robots.emplace_back();
    robot.robot = RobotId{select_robots_->ColumnText(0)};
    robot.first_seen_ns = select_robots_->ColumnInt64(1);
    robot.last_seen_ns = select_robots_->ColumnInt64(2);
    robot.state = select_robots_->ColumnText(3);
    robot.status_payload = select_robots_->ColumnBlob(4);
  }
  return robots;
}

Status MapStore::DeleteOwner(const TileOwner& owner) {
  SqliteTransaction transaction(*db_);
  FLEETMAP_RETURN_IF_ERROR(transaction.Begin());
  delete_owner_->Reset();
  FLEETMAP_RETURN_IF_ERROR(delete_owner_->BindText(1, owner.key()));
  FLEETMAP_RETURN_IF_ERROR(delete_owner_->Run());
  // Cascaded deletes are not in Changes(): count again.
  FLEETMAP_ASSIGN_OR_RETURN(const int64_t history_rows, CountHistoryRows());
  FLEETMAP_RETURN_IF_ERROR(transaction.Commit());
  history_rows_ = history_rows;
  return Status::Ok();
}

StatusOr<int64_t> MapStore::PutSession(const SessionRecord& session) {
  FLEETMAP_RETURN_IF_ERROR(ValidateSessionRecord(session).WithContext(path()));
  insert_session_->Reset();
  FLEETMAP_RETURN_IF_ERROR(insert_session_->BindText(1, session.robot.value));
  FLEETMAP_RETURN_IF_ERROR(insert_session_->Bind(2, session.started_ns));
  FLEETMAP_RETURN_IF_ERROR(insert_session_->Bind(3, session.ended_ns));
  FLEETMAP_RETURN_IF_ERROR(insert_session_->BindBlob(4, session.payload));
  FLEETMAP_RETURN_IF_ERROR(insert_session_->Run());
  return static_cast<int64_t>(sqlite3_last_insert_rowid(db_->handle()));
}

StatusOr<std::vector<SessionRecord>> MapStore::Sessions() const {
  select_sessions_->Reset();
  std::vector<SessionRecord> sessions;
  while (true) {
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, select_sessions_->Step());
    if (!row) break;
    SessionRecord& session = sessions.emplace_back();
    session.id = select_sessions_->ColumnInt64(0);
    session.robot = RobotId{select_sessions_->ColumnText(1)};
    session.started_ns = select_sessions_->ColumnInt64(2);
    session.ended_ns = select_sessions_->ColumnInt64(3);
    session.payload = select_sessions_->ColumnBlob(4);
  }
  return sessions;
}

Status MapStore::PutAdmission(const AdmissionRecord& admission) {
  if (!IsValidRobotName(admission.robot.value) || admission.admitted_ns < 0) {
    return InvalidArgumentError(path() + ": admission of '" + admission.robot.value +
                                "': not a valid robot name, or a negative time");
  }
  upsert_admission_->Reset();
  FLEETMAP_RETURN_IF_ERROR(upsert_admission_->BindText(1, admission.robot.value));
  FLEETMAP_RETURN_IF_ERROR(upsert_admission_->BindText(2, admission.operator_name));
  FLEETMAP_RETURN_IF_ERROR(upsert_admission_->Bind(3, admission.admitted_ns));
  return upsert_admission_->Run();
}

StatusOr<std::vector<AdmissionRecord>> MapStore::Admissions() const {
  select_admissions_->Reset();
  std::vector<AdmissionRecord> admissions;
  while (true) {
    FLEETMAP_ASSIGN_OR_RETURN(const bool row, select_admissions_->Step());
    if (!row) break;
    AdmissionRecord& admission = admissions.emplace_back();
    admission.robot = RobotId{select_admissions_->ColumnText(0)};
    admission.operator_name = select_admissions_->ColumnText(1);
    admission.admitted_ns = select_admissions_->ColumnInt64(2);
  }
  return admissions;
}

Status MapStore::ForEachHistoryRow(const std::function<void(const TileRecord&)>& visit) const {
  select_history_all_->Reset();
  TileRecord tile;
  while (true) {
    const StatusOr<bool> row = select_history_all_->Step();
    if (!row.ok()) {
      select_history_all_->Reset();
      return row.status();
    }
    if (!*row) break;
    tile.owner = TileOwner::FromKey(select_history_all_->ColumnText(0));
    tile.tile.x = static_cast<int32_t>(select_history_all_->ColumnInt64(1));
    tile.tile.y = static_cast<int32_t>(select_history_all_->ColumnInt64(2));
    tile.revision = static_cast<uint32_t>(select_history_all_->ColumnInt64(3));
    tile.stamp_ns = select_history_all_->ColumnInt64(4);
    tile.payload = select_history_all_->ColumnBlob(5);
    visit(tile);
  }
  select_history_all_->Reset();
  return Status::Ok();
}

StatusOr<int64_t> MapStore::HistoryRowCount() const { return CountHistoryRows(); }

Status MapStore::CheckIntegrity() const { return RunCheck("PRAGMA integrity_check"); }

}  // namespace fleetmap::store
