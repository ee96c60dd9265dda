#include "common/store/map_store.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/process/subprocess.hpp"
#include "tests/unit/store/writer_batches.hpp"

namespace fleetmap::store {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::StartsWith;

TileRecord Tile(const std::string& owner, int x, int y, uint32_t revision, int64_t stamp_ns,
                std::string payload = "") {
  if (payload.empty()) payload = owner + "@" + std::to_string(revision);
  return {TileOwner::FromKey(owner), {x, y}, revision, stamp_ns, std::move(payload)};
}

std::vector<uint32_t> Revisions(const std::vector<TileRecord>& tiles) {
  std::vector<uint32_t> out;
  for (const TileRecord& tile : tiles) out.push_back(tile.revision);
  return out;
}

// Runs SQL on the file with a separate raw connection, to set up what MapStore would never write.
void ExecRaw(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string message = error != nullptr ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << message;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

class MapStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (std::filesystem::temp_directory_path() / "map_store_test_XXXXXX");
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    path_ = (dir_ / "store.db").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::unique_ptr<MapStore> OpenOrDie(const StoreOptions& options = {}) {
    auto store = MapStore::Open(path_, options);
    EXPECT_TRUE(store.ok()) << store.status();
    return store.ok() ? std::move(store).value() : nullptr;
  }

  // A closed store file with enough history to span many pages.
  void WriteSampleStore() {
    auto store = OpenOrDie();
    ASSERT_NE(store, nullptr);
    for (int batch = 0; batch < 5; ++batch) {
      ASSERT_TRUE(store->PutTiles(testing::WriterBatch(batch)).ok());
    }
  }

  std::filesystem::path dir_;
  std::string path_;
};

// A row's owner is one of three kinds, stored as a key it is read back from.
TEST(TileOwnerTest, KeysNameTheFleetARobotAndARobotsMapFrame) {
  const TileOwner fleet = TileOwner::Fleet();
  const TileOwner robot = TileOwner::Robot(RobotId{"alpha"});
  const TileOwner map_frame = TileOwner::RobotMapFrame(RobotId{"alpha"});
  EXPECT_EQ(fleet.key(), "fleet");
  EXPECT_EQ(robot.key(), "alpha");
  EXPECT_EQ(map_frame.key(), "alpha/map");
  for (const TileOwner& owner : {fleet, robot, map_frame}) {
    EXPECT_EQ(TileOwner::FromKey(owner.key()), owner) << owner;
  }
  EXPECT_TRUE(TileOwner::FromKey("fleet").is_fleet());
  EXPECT_EQ(TileOwner::FromKey("alpha/map").robot().value, "alpha");
  EXPECT_NE(robot, map_frame);
  // A key naming no valid robot is read as one, and the record checks refuse it.
  const TileRecord bad{TileOwner::FromKey("no good/map"), {0, 0}, 1, 1, "x"};
  EXPECT_EQ(ValidateTileRecord(bad).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(ValidateTileRecord({map_frame, {0, 0}, 1, 1, "x"}).ok());
}

TEST_F(MapStoreTest, RoundTripsTiles) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const std::vector<TileRecord> tiles = {
      Tile("robot_b", -3, 7, 1, 100, std::string("bin\0ary\xff", 8)),
      Tile("fleet", 0, 0, 4, 50),
      {TileOwner::Robot(RobotId{"robot_a"}),
       {1, 2},
       2,
       300,
       ""},  // an empty payload stays empty, not NULL
  };
  ASSERT_TRUE(store->PutTiles(tiles).ok());
  const auto latest = store->LatestTiles();
  ASSERT_TRUE(latest.ok()) << latest.status();
  EXPECT_THAT(*latest, ElementsAre(tiles[1], tiles[2], tiles[0]));  // by owner, x, y
  const auto fleet = store->LatestTiles(TileOwner::FromKey("fleet"));
  ASSERT_TRUE(fleet.ok());
  EXPECT_THAT(*fleet, ElementsAre(tiles[1]));
}

TEST_F(MapStoreTest, LatestKeepsNewestRevisionAndHistoryKeepsAll) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  // Revision 2 arrives after revision 3 (out of order): it enters the history only.
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 1, 1, 1, 10), Tile("robot_a", 1, 1, 3, 30)}).ok());
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 1, 1, 2, 20)}).ok());
  const auto latest = store->LatestTiles(TileOwner::FromKey("robot_a"));
  ASSERT_TRUE(latest.ok());
  EXPECT_THAT(*latest, ElementsAre(Tile("robot_a", 1, 1, 3, 30)));
  const auto history = store->TileHistory(TileOwner::FromKey("robot_a"), {1, 1});
  ASSERT_TRUE(history.ok()) << history.status();
  EXPECT_THAT(*history, ElementsAre(Tile("robot_a", 1, 1, 1, 10), Tile("robot_a", 1, 1, 2, 20),
                                    Tile("robot_a", 1, 1, 3, 30)));
}

TEST_F(MapStoreTest, RedeliveredRevisionIsStoredOnce) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 0, 0, 5, 50)}).ok());
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 0, 0, 5, 50)}).ok());
  EXPECT_EQ(store->HistoryRowCount().value(), 1);
}

TEST_F(MapStoreTest, HistorySinceTimeStartsAtThatStamp) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  for (uint32_t revision = 1; revision <= 5; ++revision) {
    ASSERT_TRUE(store
                    ->PutTiles({Tile("robot_a", 2, 3, revision, revision * 100),
                                Tile("robot_b", 2, 3, revision, revision * 100)})
                    .ok());
  }
  const auto since = store->TileHistory(TileOwner::FromKey("robot_a"), {2, 3}, 300);
  ASSERT_TRUE(since.ok());
  EXPECT_THAT(Revisions(*since), ElementsAre(3, 4, 5));
  EXPECT_TRUE(store->TileHistory(TileOwner::FromKey("robot_a"), {2, 3}, 501)->empty());
  EXPECT_TRUE(store->TileHistory(TileOwner::FromKey("robot_a"), {3, 2})->empty());
}

TEST_F(MapStoreTest, RoundTripsRobotsAndMergesSightings) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->PutRobot({"robot_b", 100, 200, "active", "status b"}).ok());
  ASSERT_TRUE(store->PutRobot({"robot_a", 500, 600, "active", ""}).ok());
  // A later update: first_seen keeps the earliest, last_seen the latest, state is replaced.
  ASSERT_TRUE(store->PutRobot({"robot_b", 150, 900, "lost", "status b2"}).ok());
  const auto robots = store->Robots();
  ASSERT_TRUE(robots.ok()) << robots.status();
  EXPECT_THAT(*robots, ElementsAre(RobotRecord{"robot_a", 500, 600, "active", ""},
                                   RobotRecord{"robot_b", 100, 900, "lost", "status b2"}));
}

TEST_F(MapStoreTest, RefusesInvalidRobot) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const Status status = store->PutRobot({"robot_a", 0, 1, "sleeping", ""});
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("robot record 'robot_a': state 'sleeping'"));
  EXPECT_FALSE(store->PutRobot({"robot_a", 5, 1, "active", ""}).ok());
  EXPECT_FALSE(store->PutRobot({"1robot", 0, 1, "active", ""}).ok());
  EXPECT_TRUE(store->Robots()->empty());
}

TEST_F(MapStoreTest, InvalidRecordRefusesTheWholeBatch) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const Status status = store->PutTiles({Tile("robot_a", 0, 0, 1, 1), Tile("robot a", 4, 5, 1, 1)});
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), StartsWith(path_ + ": batch of 2 tiles, record 1: "));
  EXPECT_THAT(status.message(), HasSubstr("owner 'robot a' is not a valid robot name"));
  EXPECT_FALSE(store->PutTiles({Tile("robot_a", 0, 0, 1, -1)}).ok());
  EXPECT_TRUE(store->LatestTiles()->empty());
  EXPECT_EQ(store->HistoryRowCount().value(), 0);
}

TEST_F(MapStoreTest, ReopenKeepsEverything) {
  {
    auto store = OpenOrDie();
    ASSERT_NE(store, nullptr);
    ASSERT_TRUE(store->PutTiles(testing::WriterBatch(0)).ok());
    ASSERT_TRUE(store->PutTiles(testing::WriterBatch(1)).ok());
    ASSERT_TRUE(store->PutRobot({"robot_a", 1, 2, "left", "bye"}).ok());
  }
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const auto latest = store->LatestTiles(TileOwner::Robot(RobotId{testing::kWriterRobot}));
  ASSERT_TRUE(latest.ok());
  ASSERT_EQ(latest->size(), 2u * testing::kWriterTilesPerBatch);
  EXPECT_EQ(latest->front(), testing::WriterBatch(0).front());
  EXPECT_THAT(Revisions(store->TileHistory(TileOwner::FromKey("fleet"), {0, 0}).value()),
              ElementsAre(1, 2));
  EXPECT_EQ(store->HistoryRowCount().value(), 2 * (testing::kWriterTilesPerBatch + 1));
  EXPECT_THAT(store->Robots().value(), ElementsAre(RobotRecord{"robot_a", 1, 2, "left", "bye"}));
  EXPECT_TRUE(store->CheckIntegrity().ok());
}

TEST_F(MapStoreTest, ManyTilesInOneBatch) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  std::vector<TileRecord> tiles;
  for (int x = 0; x < 100; ++x) {
    for (int y = 0; y < 50; ++y) tiles.push_back(Tile("robot_a", x, y, 1, 7));
  }
  ASSERT_TRUE(store->PutTiles(tiles).ok());
  const auto latest = store->LatestTiles();
  ASSERT_TRUE(latest.ok());
  EXPECT_EQ(*latest, tiles);
  EXPECT_EQ(store->HistoryRowCount().value(), 5000);
}

TEST_F(MapStoreTest, MaxHistoryRowsDropsTheOldest) {
  StoreOptions options;
  options.max_history_rows = 5;
  {
    auto store = OpenOrDie(options);
    ASSERT_NE(store, nullptr);
    for (uint32_t revision = 1; revision <= 8; ++revision) {
      ASSERT_TRUE(store->PutTiles({Tile("robot_a", 0, 0, revision, revision)}).ok());
    }
    EXPECT_EQ(store->HistoryRowCount().value(), 5);
  }
  auto store = OpenOrDie(options);  // the count survives a reopen
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 0, 0, 9, 9), Tile("robot_a", 0, 0, 10, 10)}).ok());
  EXPECT_THAT(Revisions(store->TileHistory(TileOwner::FromKey("robot_a"), {0, 0}).value()),
              ElementsAre(6, 7, 8, 9, 10));
  EXPECT_THAT(Revisions(store->LatestTiles().value()), ElementsAre(10));
}

TEST_F(MapStoreTest, WithoutHistoryKeepsOnlyLatest) {
  StoreOptions options;
  options.keep_history = false;
  auto store = OpenOrDie(options);
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 0, 0, 1, 1), Tile("robot_a", 0, 0, 2, 2)}).ok());
  EXPECT_EQ(store->HistoryRowCount().value(), 0);
  EXPECT_THAT(Revisions(store->LatestTiles().value()), ElementsAre(2));
}

TEST_F(MapStoreTest, DeleteOwnerRemovesItsTilesAndHistory) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store
                  ->PutTiles({Tile("robot_a", 0, 0, 1, 1), Tile("robot_a", 0, 0, 2, 2),
                              Tile("robot_b", 0, 0, 1, 1)})
                  .ok());
  ASSERT_TRUE(store->PutRobot({"robot_a", 1, 2, "left", ""}).ok());
  ASSERT_TRUE(store->DeleteOwner(TileOwner::FromKey("robot_a")).ok());
  EXPECT_THAT(store->LatestTiles().value(), ElementsAre(Tile("robot_b", 0, 0, 1, 1)));
  EXPECT_TRUE(store->TileHistory(TileOwner::FromKey("robot_a"), {0, 0})->empty());
  EXPECT_EQ(store->HistoryRowCount().value(), 1);
  EXPECT_EQ(store->Robots()->size(), 1u);
  EXPECT_TRUE(store->DeleteOwner(TileOwner::FromKey("nobody")).ok());
}

TEST_F(MapStoreTest, RefusesInvalidOptions) {
  StoreOptions options;
  options.max_history_rows = -1;
  const auto store = MapStore::Open(path_, options);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(store.status().message(), HasSubstr("max_history_rows -1 is negative"));
  EXPECT_FALSE(std::filesystem::exists(path_));
}

TEST_F(MapStoreTest, MissingDirectoryIsNotFound) {
  const std::string path = (dir_ / "no_such_dir" / "store.db").string();
  const auto store = MapStore::Open(path);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(store.status().message(), StartsWith(path + ": opening: "));
}

TEST_F(MapStoreTest, RefusesAFileThatIsNotSqliteAndLeavesItAlone) {
  const std::string text = "robot_a,0,0,1\nthis is a CSV file, not a database\n";
  std::ofstream(path_, std::ios::binary) << text;
  const auto store = MapStore::Open(path_);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kDataLoss);
  EXPECT_THAT(store.status().message(), StartsWith(path_ + ": not an SQLite database: "));
  EXPECT_EQ(ReadBytes(path_), text);
}

TEST_F(MapStoreTest, RefusesAnotherApplicationsDatabase) {
  ExecRaw(path_, "CREATE TABLE invoices (id INTEGER PRIMARY KEY, amount REAL)");
  const auto store = MapStore::Open(path_);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(store.status().message(), StartsWith(path_ + ": not a fleetmap map store"));
}

TEST_F(MapStoreTest, RefusesASchemaVersionFromTheFuture) {
  WriteSampleStore();
  ExecRaw(path_, "PRAGMA user_version = 7; UPDATE store_state SET value = 1 WHERE name = 'open'");
  const auto store = MapStore::Open(path_);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(store.status().message(),
            path_ +
                ": schema version 7 is newer than this fleetmap supports (4); open it with a "
                "newer fleetmap");
  // Refused, never written: not even the open mark.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* open = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT value FROM store_state WHERE name = 'open'", -1, &open,
                               nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(open), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(open, 0), 1);
  sqlite3_finalize(open);
  sqlite3_close(db);
}

TEST_F(MapStoreTest, RefusesACorruptDatabase) {
  WriteSampleStore();
  // Overwrite the middle of the file (b-tree pages, not the header) with garbage.
  std::string bytes = ReadBytes(path_);
  ASSERT_GT(bytes.size(), 16u * 4096u);
  for (size_t i = 4096; i < bytes.size() - 4096; i += 4096) {
    std::fill_n(bytes.begin() + static_cast<std::ptrdiff_t>(i), 64, '\x5a');
  }
  std::ofstream(path_, std::ios::binary | std::ios::trunc) << bytes;
  const auto store = MapStore::Open(path_);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kDataLoss);
  EXPECT_THAT(store.status().message(), StartsWith(path_ + ": corrupt: "));
}

TEST_F(MapStoreTest, RefusesATruncatedDatabase) {
  WriteSampleStore();
  const auto size = std::filesystem::file_size(path_);
  std::filesystem::resize_file(path_, size / 2);
  const auto store = MapStore::Open(path_);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kDataLoss);
  EXPECT_THAT(store.status().message(), StartsWith(path_ + ": corrupt: "));
}

TEST_F(MapStoreTest, LockedDatabaseIsUnavailableAndTheBatchIsNotWritten) {
  StoreOptions options;
  options.busy_timeout_ms = 0;
  auto store = OpenOrDie(options);
  ASSERT_NE(store, nullptr);
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr), SQLITE_OK);
  const Status status = store->PutTiles({Tile("robot_a", 0, 0, 1, 1)});
  sqlite3_exec(other, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(other);
  EXPECT_EQ(status.code(), StatusCode::kUnavailable);
  EXPECT_THAT(status.message(), StartsWith(path_ + ": beginning a write transaction: "));
  EXPECT_TRUE(store->LatestTiles()->empty());
  EXPECT_TRUE(store->PutTiles({Tile("robot_a", 0, 0, 1, 1)}).ok());  // free again
}

// The last "committed <n>" line the writer printed completely, or -1.
int LastCommittedBatch(const std::string& output) {
  int last = -1;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    if (lines.eof()) break;  // no newline yet: the line may be cut
    if (line.rfind("committed ", 0) == 0) last = std::stoi(line.substr(10));
  }
  return last;
}

TEST_F(MapStoreTest, EveryReportedBatchSurvivesSigkill) {
  fleetmap::process::Subprocess writer({FLEETMAP_STORE_WRITER_HELPER, path_});
  ASSERT_TRUE(writer.started());
  ASSERT_TRUE(writer.WaitForOutput("committed 25\n", std::chrono::seconds(20))) << writer.Output();
  writer.Signal(SIGKILL);
  ASSERT_EQ(writer.Wait(std::chrono::seconds(10)), 128 + SIGKILL) << writer.Output();
  const int last = LastCommittedBatch(writer.StdOut());
  ASSERT_GE(last, 25);

  auto store = OpenOrDie();  // replays the WAL the killed writer left behind
  ASSERT_NE(store, nullptr);
  EXPECT_TRUE(store->CheckIntegrity().ok()) << store->CheckIntegrity();
  const auto latest = store->LatestTiles(TileOwner::Robot(RobotId{testing::kWriterRobot}));
  ASSERT_TRUE(latest.ok()) << latest.status();
  // Batches are atomic: batch `last + 1` may have committed before the kill, never in part.
  const size_t batches = latest->size() / testing::kWriterTilesPerBatch;
  ASSERT_EQ(latest->size() % testing::kWriterTilesPerBatch, 0u);
  ASSERT_GE(batches, static_cast<size_t>(last) + 1);
  for (int batch = 0; batch <= last; ++batch) {
    const std::vector<TileRecord> expected = testing::WriterBatch(batch);
    for (int i = 0; i < testing::kWriterTilesPerBatch; ++i) {
      ASSERT_EQ((*latest)[static_cast<size_t>(batch * testing::kWriterTilesPerBatch + i)],
                expected[static_cast<size_t>(i)])
          << "batch " << batch << " tile " << i;
    }
  }
  const auto fused = store->LatestTiles(TileOwner::FromKey("fleet"));
  ASSERT_TRUE(fused.ok());
  ASSERT_EQ(fused->size(), 1u);
  EXPECT_EQ(fused->front().revision, batches);
  EXPECT_EQ(store->HistoryRowCount().value(),
            static_cast<int64_t>(batches) * (testing::kWriterTilesPerBatch + 1));
  // The store is writable again after the crash.
  EXPECT_TRUE(store->PutTiles(testing::WriterBatch(static_cast<int>(batches))).ok());
}

TEST_F(MapStoreTest, SessionsRoundTripInOrderAndSurviveReopening) {
  {
    auto store = OpenOrDie();
    ASSERT_NE(store, nullptr);
    const auto first = store->PutSession({0, "alpha", 100, 200, std::string("v\0map", 5)});
    const auto second = store->PutSession({0, "beta", 150, 400, "other"});
    ASSERT_TRUE(first.ok()) << first.status();
    ASSERT_TRUE(second.ok()) << second.status();
    EXPECT_LT(*first, *second);
  }
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const auto sessions = store->Sessions();
  ASSERT_TRUE(sessions.ok()) << sessions.status();
  ASSERT_EQ(sessions->size(), 2u);
  EXPECT_EQ((*sessions)[0].robot.value, "alpha");
  EXPECT_EQ((*sessions)[0].payload, std::string("v\0map", 5));
  EXPECT_EQ((*sessions)[1].ended_ns, 400);
}

TEST_F(MapStoreTest, RefusesAnInvalidSession) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const auto backwards = store->PutSession({0, "alpha", 500, 100, ""});
  ASSERT_FALSE(backwards.ok());
  EXPECT_THAT(backwards.status().message(), HasSubstr("started_ns 500 and ended_ns 100"));
  EXPECT_FALSE(store->PutSession({0, "not a name", 0, 1, ""}).ok());
  EXPECT_TRUE(store->Sessions()->empty());
}

TEST_F(MapStoreTest, MigratesAVersionOneFileAndKeepsItsTiles) {
  WriteSampleStore();
  // What a version 1 fleetmap left: no sessions table.
  ExecRaw(path_,
          "DROP TABLE sessions; DROP TABLE tile_evidence; DROP TABLE store_state; "
          "DROP TABLE admissions; PRAGMA user_version = 1");
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  EXPECT_FALSE(store->LatestTiles()->empty());
  EXPECT_TRUE(store->Sessions()->empty());
  EXPECT_TRUE(store->PutSession({0, "alpha", 1, 2, "x"}).ok());
}

TEST_F(MapStoreTest, MigratesAVersionTwoFileAndKeepsItsTilesAndSessions) {
  {
    auto store = OpenOrDie();
    ASSERT_NE(store, nullptr);
    ASSERT_TRUE(store->PutTiles(testing::WriterBatch(0)).ok());
    ASSERT_TRUE(store->PutSession({0, "alpha", 1, 2, "x"}).ok());
  }
  // What a version 2 fleetmap left: no evidence, no store state.
  ExecRaw(path_,
          "DROP TABLE tile_evidence; DROP TABLE store_state; DROP TABLE admissions; "
          "PRAGMA user_version = 2");
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  EXPECT_EQ(store->open_report().found_version, 2);
  EXPECT_FALSE(store->open_report().unclean_close);
  EXPECT_EQ(store->LatestTiles(TileOwner::Robot(RobotId{testing::kWriterRobot}))->size(),
            static_cast<size_t>(testing::kWriterTilesPerBatch));
  EXPECT_EQ(store->Sessions()->size(), 1u);
  EXPECT_TRUE(store->Evidence()->empty());
  EXPECT_TRUE(store->Write({{}, {{"alpha", {0, 0}, 5, "evidence"}}, {}, {}}).ok());
  store.reset();
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* version = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &version, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(version), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(version, 0), MapStore::kSchemaVersion);
  sqlite3_finalize(version);
  sqlite3_close(db);
}

TEST_F(MapStoreTest, AdmissionsRoundTripTheLatestPerRobotAndRefuseBadNames) {
  {
    auto store = OpenOrDie();
    ASSERT_NE(store, nullptr);
    ASSERT_TRUE(store->PutAdmission({RobotId{"beta"}, "night shift", 10}).ok());
    ASSERT_TRUE(store->PutAdmission({RobotId{"alpha"}, "", 20}).ok());
    ASSERT_TRUE(store->PutAdmission({RobotId{"beta"}, "day shift", 30}).ok());
    EXPECT_FALSE(store->PutAdmission({RobotId{"not a name"}, "", 1}).ok());
    EXPECT_FALSE(store->PutAdmission({RobotId{"gamma"}, "", -1}).ok());
  }
  auto store = OpenOrDie();  // they outlive the process that wrote them
  ASSERT_NE(store, nullptr);
  const auto admissions = store->Admissions();
  ASSERT_TRUE(admissions.ok());
  EXPECT_EQ(*admissions, (std::vector<AdmissionRecord>{{RobotId{"alpha"}, "", 20},
                                                       {RobotId{"beta"}, "day shift", 30}}));
}

TEST_F(MapStoreTest, MigratesAVersionThreeFileToOneThatKeepsAdmissions) {
  WriteSampleStore();
  ExecRaw(path_, "DROP TABLE admissions; PRAGMA user_version = 3");
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  EXPECT_EQ(store->open_report().found_version, 3);
  EXPECT_FALSE(store->LatestTiles()->empty());
  EXPECT_TRUE(store->Admissions()->empty());
  EXPECT_TRUE(store->PutAdmission({RobotId{"alpha"}, "op", 1}).ok());
  EXPECT_EQ(store->Admissions()->size(), 1u);
}

TEST_F(MapStoreTest, EvidenceRowsAreReplacedAndRoundTrip) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const std::string binary("z\0\xff", 3);
  ASSERT_TRUE(
      store->Write({{}, {{"alpha", {0, 0}, 5, "old"}, {"beta", {-1, 2}, 6, binary}}, {}, {}}).ok());
  ASSERT_TRUE(store->Write({{}, {{"alpha", {0, 0}, 9, "new"}}, {}, {}}).ok());
  const auto evidence = store->Evidence();
  ASSERT_TRUE(evidence.ok()) << evidence.status();
  EXPECT_THAT(*evidence, ElementsAre(EvidenceRecord{RobotId{"alpha"}, {0, 0}, 9, "new"},
                                     EvidenceRecord{RobotId{"beta"}, {-1, 2}, 6, binary}));
  const Status refused = store->Write({{}, {{"", {0, 0}, 1, "x"}}, {}, {}});
  EXPECT_EQ(refused.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(refused.message(), HasSubstr("evidence record 0"));
}

TEST_F(MapStoreTest, RemovedTileLosesItsRowsHistoryAndEvidenceOnly) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store
                  ->Write({{Tile("alpha", 0, 0, 1, 10), Tile("alpha", 0, 0, 2, 20),
                            Tile("alpha", 1, 0, 1, 10), Tile("beta", 0, 0, 1, 10)},
                           {{"alpha", {0, 0}, 20, "a00"}, {"alpha", {1, 0}, 10, "a10"}},
                           {},
                           {{"alpha", 1, 20, "active", ""}}})
                  .ok());
  ASSERT_EQ(store->HistoryRowCount().value(), 4);
  // The robot disposed tile (0, 0); in the same batch a fused revision arrives.
  ASSERT_TRUE(store
                  ->Write({{Tile("fleet", 0, 0, 1, 30)},
                           {},
                           {{TileOwner::Robot(RobotId{"alpha"}), {0, 0}}},
                           {}})
                  .ok());
  const auto latest = store->LatestTiles();
  ASSERT_TRUE(latest.ok());
  std::vector<std::string> keys;
  for (const TileRecord& tile : *latest) {
    keys.push_back(tile.owner.key() + " " + std::to_string(tile.tile.x));
  }
  EXPECT_THAT(keys, ElementsAre("alpha 1", "beta 0", "fleet 0"));
  EXPECT_TRUE(store->TileHistory(TileOwner::FromKey("alpha"), {0, 0})->empty());
  EXPECT_EQ(store->HistoryRowCount().value(), 3);
  EXPECT_THAT(*store->Evidence(), ElementsAre(EvidenceRecord{RobotId{"alpha"}, {1, 0}, 10, "a10"}));
  EXPECT_EQ(store->Robots()->size(), 1u);
  // Removing a key the store does not hold is not an error.
  EXPECT_TRUE(store->Write({{}, {}, {{TileOwner::Robot(RobotId{"gamma"}), {5, 5}}}, {}}).ok());
}

TEST_F(MapStoreTest, RemovalsCountTowardsTheHistoryLimit) {
  StoreOptions options;
  options.max_history_rows = 3;
  auto store = OpenOrDie(options);
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store
                  ->PutTiles({Tile("alpha", 0, 0, 1, 1), Tile("alpha", 0, 0, 2, 2),
                              Tile("alpha", 1, 0, 1, 1)})
                  .ok());
  ASSERT_TRUE(store->Write({{}, {}, {{TileOwner::Robot(RobotId{"alpha"}), {0, 0}}}, {}}).ok());
  // One row left: two more fit without dropping the (1, 0) row.
  ASSERT_TRUE(store->PutTiles({Tile("alpha", 2, 0, 1, 1), Tile("alpha", 3, 0, 1, 1)}).ok());
  EXPECT_EQ(store->HistoryRowCount().value(), 3);
  EXPECT_EQ(store->TileHistory(TileOwner::FromKey("alpha"), {1, 0})->size(), 1u);
}

TEST_F(MapStoreTest, RefusesAnEmptyFileAndSaysHowToStartFresh) {
  std::ofstream(path_, std::ios::binary | std::ios::trunc).flush();
  ASSERT_EQ(std::filesystem::file_size(path_), 0u);
  const auto store = MapStore::Open(path_);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kDataLoss);
  EXPECT_THAT(store.status().message(), StartsWith(path_ + ": the file is empty (0 bytes)"));
  EXPECT_THAT(store.status().message(), HasSubstr("To start a new map, delete it"));
  EXPECT_EQ(std::filesystem::file_size(path_), 0u);  // left alone
}

TEST_F(MapStoreTest, ReportsANewStoreAndACleanClose) {
  {
    auto store = OpenOrDie();
    ASSERT_NE(store, nullptr);
    EXPECT_TRUE(store->open_report().created);
    EXPECT_EQ(store->open_report().Summary(), "created a new store");
    ASSERT_TRUE(store->PutTiles(testing::WriterBatch(0)).ok());
  }
  EXPECT_FALSE(std::filesystem::exists(path_ + "-wal"));  // folded back on close
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const StoreOpenReport& report = store->open_report();
  EXPECT_FALSE(report.created);
  EXPECT_EQ(report.found_version, MapStore::kSchemaVersion);
  EXPECT_TRUE(report.quick_checked);
  EXPECT_FALSE(report.unclean_close);
  EXPECT_FALSE(report.wal_found);
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_EQ(report.Summary(), "schema version 4, quick check ok, closed cleanly");
}

// Runs store_writer_helper for `batches` commits, then SIGKILLs it with the store open.
void KillWriterAfter(const std::string& path, int batches) {
  fleetmap::process::Subprocess writer(
      {FLEETMAP_STORE_WRITER_HELPER, path, std::to_string(batches + 1)});
  ASSERT_TRUE(writer.started());
  ASSERT_TRUE(
      writer.WaitForOutput("committed " + std::to_string(batches) + "\n", std::chrono::seconds(20)))
      << writer.Output();
  writer.Signal(SIGKILL);
  ASSERT_EQ(writer.Wait(std::chrono::seconds(10)), 128 + SIGKILL) << writer.Output();
}

TEST_F(MapStoreTest, ReportsAKilledWriterAndWhatItsWalGaveBack) {
  KillWriterAfter(path_, 5);
  ASSERT_TRUE(std::filesystem::exists(path_ + "-wal"));
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const StoreOpenReport& report = store->open_report();
  EXPECT_TRUE(report.unclean_close);
  EXPECT_TRUE(report.wal_found);
  EXPECT_GT(report.wal_bytes, 0);
  EXPECT_GT(report.wal_frames_recovered, 0);
  EXPECT_TRUE(report.warnings.empty()) << report.Summary();
  EXPECT_THAT(report.Summary(), HasSubstr("not closed by its last writer (WAL of"));
  EXPECT_GE(store->LatestTiles(TileOwner::Robot(RobotId{testing::kWriterRobot}))->size(),
            6u * testing::kWriterTilesPerBatch);
}

TEST_F(MapStoreTest, WarnsWhenAKilledWritersWalIsMissing) {
  KillWriterAfter(path_, 5);
  ASSERT_TRUE(std::filesystem::remove(path_ + "-wal"));
  std::filesystem::remove(path_ + "-shm");
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const StoreOpenReport& report = store->open_report();
  EXPECT_TRUE(report.unclean_close);
  EXPECT_FALSE(report.wal_found);
  ASSERT_EQ(report.warnings.size(), 1u) << report.Summary();
  EXPECT_THAT(report.warnings[0], HasSubstr("its write-ahead log " + path_ + "-wal is missing"));
  EXPECT_THAT(report.Summary(), HasSubstr("WARNING: "));
  // Opened (and closed) again, the store is clean: the warning is not repeated for ever.
  store.reset();
  EXPECT_TRUE(OpenOrDie()->open_report().warnings.empty());
}

TEST_F(MapStoreTest, WarnsWhenAKilledWritersWalIsDamaged) {
  KillWriterAfter(path_, 5);
  std::string wal = ReadBytes(path_ + "-wal");
  ASSERT_GT(wal.size(), 32u + 3u * (24u + 4096u));
  // Scramble the page of the second frame: SQLite stops replaying there.
  for (size_t i = 32 + (24 + 4096) + 24; i < 32 + 2 * (24 + 4096); i += 7) wal[i] ^= 0x55;
  std::ofstream(path_ + "-wal", std::ios::binary | std::ios::trunc) << wal;
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const StoreOpenReport& report = store->open_report();
  EXPECT_TRUE(report.unclean_close);
  ASSERT_EQ(report.warnings.size(), 1u) << report.Summary();
  EXPECT_THAT(report.warnings[0], HasSubstr(path_ + "-wal is damaged: recovery replayed "));
  EXPECT_THAT(report.warnings[0], HasSubstr("frame 2 fails its checksum"));
  EXPECT_THAT(report.warnings[0], HasSubstr(" committed transactions among the dropped frames"));
  EXPECT_FALSE(report.wal_ends_mid_frame);
  EXPECT_GE(report.wal_commits_dropped, 5);  // batches 1..5 at least, after the damaged frame
  EXPECT_GT(report.wal_frames_dropped, 0);
  EXPECT_EQ(report.wal_bytes_dropped, report.wal_frames_dropped * (24 + 4096));
}

// The probe's case: a killed writer's WAL cut in the middle of a frame. SQLite keeps the
// transactions before the cut without a word; the store says what it dropped.
TEST_F(MapStoreTest, ReportsAWalCutMidFrameWithWhatRecoveryDropped) {
  KillWriterAfter(path_, 5);
  const std::string wal = ReadBytes(path_ + "-wal");
  const size_t frame = 24 + 4096;
  const size_t frames = (wal.size() - 32) / frame;
  ASSERT_GT(frames, 8u);
  const size_t cut = 32 + frames / 2 * frame + 100;  // half way, 100 bytes into a frame
  std::ofstream(path_ + "-wal", std::ios::binary | std::ios::trunc) << wal.substr(0, cut);
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const StoreOpenReport& report = store->open_report();
  ASSERT_EQ(report.warnings.size(), 1u) << report.Summary();
  const std::string& warning = report.warnings[0];
  EXPECT_THAT(warning, HasSubstr(path_ + "-wal is damaged: recovery replayed "));
  EXPECT_THAT(warning, HasSubstr("the file ends mid-frame (frame " +
                                 std::to_string(frames / 2 + 1) + " has 100 of 4120 bytes"));
  EXPECT_TRUE(report.wal_ends_mid_frame);
  // The killed writer's -shm still counts every frame it committed: the cut lost at least one
  // committed transaction, and as many frames as the cut took.
  EXPECT_EQ(report.wal_committed_frames_lost,
            static_cast<int64_t>(frames) - report.wal_frames_recovered);
  EXPECT_GE(report.wal_commits_dropped, 1);
  EXPECT_THAT(warning, HasSubstr("its last writer's -shm counts " + std::to_string(frames) +
                                 " committed frames"));
  // What the warning says was kept is what the store holds: whole batches, fewer than 6.
  const auto latest = store->LatestTiles(TileOwner::Robot(RobotId{testing::kWriterRobot}));
  ASSERT_TRUE(latest.ok());
  EXPECT_LT(latest->size(), 6u * testing::kWriterTilesPerBatch);
  EXPECT_EQ(latest->size() % testing::kWriterTilesPerBatch, 0u);
  const size_t batches = latest->size() / testing::kWriterTilesPerBatch;
  EXPECT_THAT(warning, HasSubstr("recovery replayed " + std::to_string(batches) + " transactions"));
  EXPECT_THAT(warning, HasSubstr("The newest revision kept is "));
  EXPECT_THAT(warning, HasSubstr(") revision " + std::to_string(batches) + " of 1970-01-01T"));
  EXPECT_TRUE(store->CheckIntegrity().ok());
}

// Without the -shm, the frames past the cut cannot be counted; the cut itself is still reported.
TEST_F(MapStoreTest, ReportsAWalCutMidFrameWithoutItsShm) {
  KillWriterAfter(path_, 5);
  const std::string wal = ReadBytes(path_ + "-wal");
  const size_t frame = 24 + 4096;
  const size_t frames = (wal.size() - 32) / frame;
  ASSERT_GT(frames, 8u);
  std::ofstream(path_ + "-wal", std::ios::binary | std::ios::trunc)
      << wal.substr(0, 32 + frames / 2 * frame + 24);
  ASSERT_TRUE(std::filesystem::remove(path_ + "-shm"));
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const StoreOpenReport& report = store->open_report();
  ASSERT_EQ(report.warnings.size(), 1u) << report.Summary();
  EXPECT_THAT(report.warnings[0], HasSubstr("the file ends mid-frame"));
  EXPECT_TRUE(report.wal_ends_mid_frame);
  EXPECT_EQ(report.wal_committed_frames_lost, 0);
  EXPECT_GE(report.wal_frames_dropped, 1);
}

// A WAL SQLite replays whole (a killed writer's, left alone) is no loss: no warning.
TEST_F(MapStoreTest, AWholeWalOfAKilledWriterDropsNothing) {
  KillWriterAfter(path_, 5);
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const StoreOpenReport& report = store->open_report();
  EXPECT_TRUE(report.warnings.empty()) << report.Summary();
  EXPECT_EQ(report.wal_frames_dropped, 0);
  EXPECT_EQ(report.wal_commits_dropped, 0);
  EXPECT_FALSE(report.wal_ends_mid_frame);
}

TEST_F(MapStoreTest, ASecondWriterIsRefusedNamingTheHoldersPid) {
  // A writer process holds the store (it committed one batch and waits).
  fleetmap::process::Subprocess writer({FLEETMAP_STORE_WRITER_HELPER, path_, "1"});
  ASSERT_TRUE(writer.started());
  ASSERT_TRUE(writer.WaitForOutput("committed 0\n", std::chrono::seconds(20))) << writer.Output();
  EXPECT_EQ(StoreLock::RecordedHolder(path_), writer.pid());
  const auto refused = MapStore::Open(path_);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(refused.status().message(),
              StartsWith(path_ + ": the map store is in use by another writer (process " +
                         std::to_string(writer.pid()) + " holds " + path_ + ".lock)"));
  // Plain SQLite readers are not blocked by the lock.
  sqlite3* reader = nullptr;
  ASSERT_EQ(sqlite3_open_v2(path_.c_str(), &reader, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  EXPECT_EQ(sqlite3_exec(reader, "SELECT count(*) FROM tile_latest", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(reader);
  writer.Signal(SIGKILL);
  ASSERT_EQ(writer.Wait(std::chrono::seconds(10)), 128 + SIGKILL);
  // The kernel released the killed holder's lock; its pid left in the file blocks nothing.
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  EXPECT_EQ(StoreLock::RecordedHolder(path_), getpid());
}

TEST_F(MapStoreTest, AWaitingWriterGetsTheStoreOnceItsHolderExits) {
  auto writer = std::make_unique<fleetmap::process::Subprocess>(
      std::vector<std::string>{FLEETMAP_STORE_WRITER_HELPER, path_, "1"});
  ASSERT_TRUE(writer->started());
  ASSERT_TRUE(writer->WaitForOutput("committed 0\n", std::chrono::seconds(20))) << writer->Output();
  const pid_t holder = writer->pid();
  StoreOptions options;
  options.lock_timeout_ms = 60'000;  // a bound for a loaded machine; the holder goes at once
  std::vector<std::string> notices;
  // Told once that it waits, and for whom; then the holder exits.
  const auto store = MapStore::Open(path_, options, [&](const std::string& notice) {
    notices.push_back(notice);
    writer->Signal(SIGKILL);
  });
  ASSERT_TRUE(store.ok()) << store.status();
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_EQ(notices[0], path_ + " is in use by process " + std::to_string(holder) +
                            ": waiting up to 60 s for it to close the store");
  EXPECT_EQ((*store)->LatestTiles(TileOwner::Robot(RobotId{testing::kWriterRobot}))->size(),
            static_cast<size_t>(testing::kWriterTilesPerBatch));
  EXPECT_EQ(writer->Wait(std::chrono::seconds(10)), 128 + SIGKILL);
}

TEST_F(MapStoreTest, OneProcessCannotOpenAStoreTwice) {
  auto first = OpenOrDie();
  ASSERT_NE(first, nullptr);
  const auto second = MapStore::Open(path_);
  ASSERT_FALSE(second.ok());
  EXPECT_THAT(second.status().message(),
              HasSubstr("in use by another writer (process " + std::to_string(getpid())));
  first.reset();
  EXPECT_NE(OpenOrDie(), nullptr);
}

TEST_F(MapStoreTest, HistoryRowsAreVisitedOneByOneOldestFirst) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->PutTiles({Tile("alpha", 0, 0, 1, 10), Tile("beta", 1, 0, 1, 10)}).ok());
  ASSERT_TRUE(store->PutTiles({Tile("alpha", 0, 0, 2, 20)}).ok());
  std::vector<std::string> visited;
  ASSERT_TRUE(store
                  ->ForEachHistoryRow([&](const TileRecord& row) {
                    visited.push_back(row.owner.key() + "@" + std::to_string(row.revision));
                  })
                  .ok());
  EXPECT_THAT(visited, ElementsAre("alpha@1", "beta@1", "alpha@2"));
}

TEST_F(MapStoreTest, FullFileFailsAsDiskFullAndKeepsEarlierCommits) {
  StoreOptions options;
  options.max_page_count = 40;
  auto store = OpenOrDie(options);
  ASSERT_NE(store, nullptr);
  Status status;
  int committed = 0;
  for (; committed < 100; ++committed) {
    status = store->PutTiles(testing::WriterBatch(committed));
    if (!status.ok()) break;
  }
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), StatusCode::kResourceExhausted) << status;
  EXPECT_THAT(status.message(), HasSubstr("database or disk is full"));
  EXPECT_EQ(store->LatestTiles(TileOwner::Robot(RobotId{testing::kWriterRobot}))->size(),
            static_cast<size_t>(committed * testing::kWriterTilesPerBatch));
}

}  // namespace
}  // namespace fleetmap::store
