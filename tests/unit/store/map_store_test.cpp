#include "common/store/map_store.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdlib.h>

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
  return {owner, {x, y}, revision, stamp_ns, std::move(payload)};
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

TEST_F(MapStoreTest, RoundTripsTiles) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  const std::vector<TileRecord> tiles = {
      Tile("robot_b", -3, 7, 1, 100, std::string("bin\0ary\xff", 8)),
      Tile(kFleetOwner, 0, 0, 4, 50),
      {"robot_a", {1, 2}, 2, 300, ""},  // an empty payload stays empty, not NULL
  };
  ASSERT_TRUE(store->PutTiles(tiles).ok());
  const auto latest = store->LatestTiles();
  ASSERT_TRUE(latest.ok()) << latest.status();
  EXPECT_THAT(*latest, ElementsAre(tiles[1], tiles[2], tiles[0]));  // by owner, x, y
  const auto fleet = store->LatestTiles(kFleetOwner);
  ASSERT_TRUE(fleet.ok());
  EXPECT_THAT(*fleet, ElementsAre(tiles[1]));
}

TEST_F(MapStoreTest, LatestKeepsNewestRevisionAndHistoryKeepsAll) {
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  // Revision 2 arrives after revision 3 (out of order): it enters the history only.
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 1, 1, 1, 10), Tile("robot_a", 1, 1, 3, 30)}).ok());
  ASSERT_TRUE(store->PutTiles({Tile("robot_a", 1, 1, 2, 20)}).ok());
  const auto latest = store->LatestTiles("robot_a");
  ASSERT_TRUE(latest.ok());
  EXPECT_THAT(*latest, ElementsAre(Tile("robot_a", 1, 1, 3, 30)));
  const auto history = store->TileHistory("robot_a", {1, 1});
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
  const auto since = store->TileHistory("robot_a", {2, 3}, 300);
  ASSERT_TRUE(since.ok());
  EXPECT_THAT(Revisions(*since), ElementsAre(3, 4, 5));
  EXPECT_TRUE(store->TileHistory("robot_a", {2, 3}, 501)->empty());
  EXPECT_TRUE(store->TileHistory("robot_a", {3, 2})->empty());
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
  const auto latest = store->LatestTiles(testing::kWriterRobot);
  ASSERT_TRUE(latest.ok());
  ASSERT_EQ(latest->size(), 2u * testing::kWriterTilesPerBatch);
  EXPECT_EQ(latest->front(), testing::WriterBatch(0).front());
  EXPECT_THAT(Revisions(store->TileHistory(kFleetOwner, {0, 0}).value()), ElementsAre(1, 2));
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
  EXPECT_THAT(Revisions(store->TileHistory("robot_a", {0, 0}).value()),
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
  ASSERT_TRUE(store->DeleteOwner("robot_a").ok());
  EXPECT_THAT(store->LatestTiles().value(), ElementsAre(Tile("robot_b", 0, 0, 1, 1)));
  EXPECT_TRUE(store->TileHistory("robot_a", {0, 0})->empty());
  EXPECT_EQ(store->HistoryRowCount().value(), 1);
  EXPECT_EQ(store->Robots()->size(), 1u);
  EXPECT_TRUE(store->DeleteOwner("nobody").ok());
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
  ExecRaw(path_, "PRAGMA user_version = 7");
  const auto store = MapStore::Open(path_);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(store.status().message(),
            path_ +
                ": schema version 7 is newer than this fleetmap supports (2); open it with a "
                "newer fleetmap");
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
  const auto latest = store->LatestTiles(testing::kWriterRobot);
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
  const auto fused = store->LatestTiles(kFleetOwner);
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
  EXPECT_EQ((*sessions)[0].robot, "alpha");
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
  ExecRaw(path_, "DROP TABLE sessions; PRAGMA user_version = 1");
  auto store = OpenOrDie();
  ASSERT_NE(store, nullptr);
  EXPECT_FALSE(store->LatestTiles()->empty());
  EXPECT_TRUE(store->Sessions()->empty());
  EXPECT_TRUE(store->PutSession({0, "alpha", 1, 2, "x"}).ok());
}

}  // namespace
}  // namespace fleetmap::store
