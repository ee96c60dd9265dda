#include "server/session_grids.hpp"

#include <gtest/gtest.h>

#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::server {
namespace {

// A room of free cells with a solid box at `box` (0.4 m square), `origin` its map origin.
grid::OccupancyGrid Room(const Point2& box, const Pose2& origin, int cells = 120) {
  grid::OccupancyGrid map(cells, cells, 0.05, origin, grid::kFreeValue);
  for (int y = 0; y < cells; ++y) {
    for (int x = 0; x < cells; ++x) {
      const Point2 p = map.CellCenter(x, y);
      if (std::abs(p.x() - box.x()) < 0.2 && std::abs(p.y() - box.y()) < 0.2) {
        map.at(x, y) = grid::kOccupiedValue;
      }
    }
  }
  return map;
}

MappingSession Session(int64_t id, const grid::OccupancyGrid& map) {
  auto tiled = vector_map::VectorizeTiled(map, Transform2::Identity());
  EXPECT_TRUE(tiled.ok()) << tiled.status();
  MappingSession session;
  session.id = id;
  session.robot = RobotId{"robot" + std::to_string(id)};
  session.map = *std::move(tiled);
  return session;
}

// Occupied cells within the 0.4 m box centred at `box`.
int OccupiedInBox(const grid::OccupancyGrid& grid, const Point2& box) {
  int occupied = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const Point2 p = grid.CellCenter(x, y);
      if (std::abs(p.x() - box.x()) < 0.2 && std::abs(p.y() - box.y()) < 0.2 &&
          grid.StateAt(x, y) == grid::CellState::kOccupied) {
        ++occupied;
      }
    }
  }
  return occupied;
}

grid::CellState StateAt(const grid::OccupancyGrid& grid, const Point2& point) {
  const auto cell = grid.CellAt(point);
  return cell ? grid.StateAt(cell->x, cell->y) : grid::CellState::kUnknown;
}

TEST(SessionGridsTest, SessionsShareOneGeometryAndKeepTheirOwnCells) {
  const std::vector<MappingSession> sessions = {
      Session(1, Room({1.5, 1.5}, Pose2{0.0, 0.0, 0.0})),
      Session(2, Room({4.0, 4.0}, Pose2{2.0, 2.0, 0.0})),  // overlaps, reaches further
  };
  fusion::FusionOptions options;
  const auto grids = SessionGrids(sessions, options);
  ASSERT_TRUE(grids.ok()) << grids.status();
  ASSERT_EQ(grids->size(), 2u);
  const grid::OccupancyGrid& first = (*grids)[0];
  const grid::OccupancyGrid& second = (*grids)[1];
  EXPECT_EQ(first.width(), second.width());
  EXPECT_EQ(first.height(), second.height());
  EXPECT_EQ(first.origin(), second.origin());
  // Each session's box is where it stood (at least its outline), and free in the other.
  EXPECT_GE(OccupiedInBox(first, {1.5, 1.5}), 28);
  EXPECT_GE(OccupiedInBox(second, {4.0, 4.0}), 28);
  EXPECT_EQ(OccupiedInBox(first, {4.0, 4.0}), 0);
  EXPECT_EQ(StateAt(first, {4.0, 4.0}), grid::CellState::kFree);
  EXPECT_EQ(StateAt(second, {3.0, 3.0}), grid::CellState::kFree);
  // What a session never saw is unknown.
  EXPECT_EQ(StateAt(first, {7.5, 7.5}), grid::CellState::kUnknown);
  EXPECT_EQ(StateAt(second, {1.0, 1.0}), grid::CellState::kUnknown);
}

TEST(SessionGridsTest, ASessionFarAwayDoesNotStretchEveryGrid) {
  // Two sessions of one building and a third 50 km away: one grid spanning all would hold 1e12
  // cells. The grids cover the building, which two sessions mapped.
  const std::vector<MappingSession> sessions = {
      Session(1, Room({1.5, 1.5}, Pose2{0.0, 0.0, 0.0})),
      Session(2, Room({4.0, 4.0}, Pose2{2.0, 2.0, 0.0})),
      Session(3, Room({50001.5, 1.5}, Pose2{50000.0, 0.0, 0.0})),
  };
  const auto grids = SessionGrids(sessions, fusion::FusionOptions{});
  ASSERT_TRUE(grids.ok()) << grids.status();
  ASSERT_EQ(grids->size(), 3u);
  for (const grid::OccupancyGrid& grid : *grids) {
    EXPECT_LE(grid.width(), 400);
    EXPECT_LE(grid.height(), 400);
  }
  EXPECT_GE(OccupiedInBox((*grids)[0], {1.5, 1.5}), 28);
  EXPECT_EQ((*grids)[2].StateAt(0, 0), grid::CellState::kUnknown);
}

TEST(SessionGridsTest, AMemoryBoundCutsTheWindowToFewerTiles) {
  // Two sessions on two neighbouring 10 m tiles: together 400 x 200 cells at 5 cm.
  const std::vector<MappingSession> sessions = {
      Session(1, Room({1.5, 1.5}, Pose2{0.0, 0.0, 0.0})),
      Session(2, Room({13.5, 1.5}, Pose2{12.0, 0.0, 0.0})),
  };
  const auto whole = SessionGrids(sessions, fusion::FusionOptions{});
  ASSERT_TRUE(whole.ok()) << whole.status();
  EXPECT_EQ((*whole)[0].width(), 400);
  // One tile's cells at most: the window holds one of the two tiles, with its session's box.
  const auto bounded = SessionGrids(sessions, fusion::FusionOptions{}, 200 * 200);
  ASSERT_TRUE(bounded.ok()) << bounded.status();
  for (const grid::OccupancyGrid& grid : *bounded) {
    EXPECT_EQ(grid.width(), 200);
    EXPECT_EQ(grid.height(), 200);
  }
  EXPECT_GE(OccupiedInBox((*bounded)[0], {1.5, 1.5}) + OccupiedInBox((*bounded)[1], {13.5, 1.5}),
            28);
}

TEST(SessionGridsTest, NoSessionsGiveNoGrids) {
  const auto grids = SessionGrids({}, fusion::FusionOptions{});
  ASSERT_TRUE(grids.ok());
  EXPECT_TRUE(grids->empty());
}

}  // namespace
}  // namespace fleetmap::server
