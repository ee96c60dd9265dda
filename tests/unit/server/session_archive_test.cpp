#include "server/session_archive.hpp"

#include <gtest/gtest.h>

namespace fleetmap::server {
namespace {

vector_map::VectorMap SomeTile() {
  vector_map::VectorMap map;
  vector_map::Polyline wall;
  wall.points = {Point2(0.1, 0.1), Point2(1.0, 0.1)};
  map.obstacles.push_back(wall);
  return map;
}

TEST(SessionArchiveTest, LateTilesAfterASessionEndedDoNotMakeANewSession) {
  SessionArchive archive(10.0, nullptr, 12);
  archive.RecordTile(RobotId{"alpha"}, {0, 0}, SomeTile(), Timestamp{});
  auto first = archive.EndSession(RobotId{"alpha"}, Timestamp{});
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(first->has_value());
  // A sample still in flight when alpha left, then the writer vanishes (alpha "lost").
  archive.RecordTile(RobotId{"alpha"}, {1, 0}, SomeTile(), Timestamp{});
  auto late = archive.EndSession(RobotId{"alpha"}, Timestamp{});
  ASSERT_TRUE(late.ok());
  EXPECT_FALSE(late->has_value());
  EXPECT_EQ(archive.finished().size(), 1u);
}

TEST(SessionArchiveTest, ARobotThatComesBackStartsANewSessionWithItsFirstTiles) {
  SessionArchive archive(10.0, nullptr, 12);
  archive.RecordTile(RobotId{"alpha"}, {0, 0}, SomeTile(), Timestamp{});
  ASSERT_TRUE(archive.EndSession(RobotId{"alpha"}, Timestamp{}).ok());
  // Its first tiles may arrive before the server has seen it rejoin, or after.
  archive.RecordTile(RobotId{"alpha"}, {2, 0}, SomeTile(), Timestamp{});
  archive.Rejoin(RobotId{"alpha"});
  archive.RecordTile(RobotId{"alpha"}, {3, 0}, SomeTile(), Timestamp{});
  auto second = archive.EndSession(RobotId{"alpha"}, Timestamp{});
  ASSERT_TRUE(second.ok());
  ASSERT_TRUE(second->has_value());
  EXPECT_EQ((*second)->map.tiles.size(), 2u);
  EXPECT_GT((*second)->id, archive.finished().front().id);
  EXPECT_EQ(archive.finished().size(), 2u);
}

TEST(SessionArchiveTest, ASessionWithoutTilesIsNotArchived) {
  SessionArchive archive(10.0, nullptr, 12);
  auto none = archive.EndSession(RobotId{"beta"}, Timestamp{});
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
  EXPECT_TRUE(archive.finished().empty());
}

TEST(SessionArchiveTest, MemoryHoldsTheNewestSessionsAndCountsThemAll) {
  SessionArchive archive(10.0, nullptr, 2);
  for (const char* name : {"a", "b", "c"}) {
    archive.RecordTile(RobotId{name}, {0, 0}, SomeTile(), Timestamp{});
    ASSERT_TRUE(archive.EndSession(RobotId{name}, Timestamp{}).ok());
  }
  ASSERT_EQ(archive.finished().size(), 2u);
  EXPECT_EQ(archive.finished().front().robot, RobotId{"b"});
  EXPECT_EQ(archive.finished().back().robot, RobotId{"c"});
  EXPECT_EQ(archive.finished_count(), 3u);
}

TEST(SessionArchiveTest, ADiscardedSessionIsNotArchivedAndItsLateTilesMakeNoSession) {
  SessionArchive archive(10.0, nullptr, 12);
  archive.RecordTile(RobotId{"flooder"}, {0, 0}, SomeTile(), Timestamp{});
  archive.RecordTile(RobotId{"flooder"}, {1, 0}, SomeTile(), Timestamp{});
  EXPECT_TRUE(archive.has_open_session(RobotId{"flooder"}));
  EXPECT_EQ(archive.DiscardSession(RobotId{"flooder"}), 2u);
  EXPECT_FALSE(archive.has_open_session(RobotId{"flooder"}));
  archive.RecordTile(RobotId{"flooder"}, {2, 0}, SomeTile(), Timestamp{});
  auto late = archive.EndSession(RobotId{"flooder"}, Timestamp{});
  ASSERT_TRUE(late.ok());
  EXPECT_FALSE(late->has_value());
  EXPECT_TRUE(archive.finished().empty());
  EXPECT_EQ(archive.finished_count(), 0u);
}

}  // namespace
}  // namespace fleetmap::server
