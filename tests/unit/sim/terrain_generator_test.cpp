#include "common/sim/terrain_generator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <vector>

#include "common/sim/terrain_geojson.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::sim {
namespace {

grid::OccupancyGrid Truth(TerrainKind kind, double size, uint32_t seed) {
  const StatusOr<TerrainGenerator> generator =
      TerrainGenerator::Create({.kind = kind, .size = size, .seed = seed});
  EXPECT_TRUE(generator.ok()) << generator.status();
  const StatusOr<grid::OccupancyGrid> truth = RasterizeTerrain(generator->Generate(), 0.05);
  EXPECT_TRUE(truth.ok()) << truth.status();
  return *truth;
}

// Free cells reachable from `start` through free 4-neighbours.
int64_t ReachableFree(const grid::OccupancyGrid& grid, const Point2& start) {
  std::vector<uint8_t> seen(static_cast<size_t>(grid.cell_count()), 0);
  const grid::CellIndex s = *grid.CellAt(start);
  std::deque<grid::CellIndex> queue = {s};
  seen[static_cast<size_t>(s.y) * grid.width() + s.x] = 1;
  int64_t count = 0;
  while (!queue.empty()) {
    const grid::CellIndex c = queue.front();
    queue.pop_front();
    ++count;
    const int dx[4] = {1, -1, 0, 0};
    const int dy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int x = c.x + dx[k];
      const int y = c.y + dy[k];
      if (!grid.Contains(x, y) || grid.at(x, y) != grid::kFreeValue) continue;
      uint8_t& flag = seen[static_cast<size_t>(y) * grid.width() + x];
      if (flag) continue;
      flag = 1;
      queue.push_back({x, y});
    }
  }
  return count;
}

class TerrainKinds : public ::testing::TestWithParam<TerrainKind> {};

TEST_P(TerrainKinds, SameSeedSameTerrainOtherSeedOtherTerrain) {
  const grid::OccupancyGrid a = Truth(GetParam(), 20.0, 7);
  const grid::OccupancyGrid b = Truth(GetParam(), 20.0, 7);
  const grid::OccupancyGrid c = Truth(GetParam(), 20.0, 8);
  EXPECT_EQ(a.data(), b.data());
  EXPECT_NE(a.data(), c.data());
  const TerrainGenerator generator =
      *TerrainGenerator::Create({.kind = GetParam(), .size = 20.0, .seed = 7});
  EXPECT_EQ(*TerrainToGeoJsonString(generator.Generate()),
            *TerrainToGeoJsonString(generator.Generate()));
}

TEST_P(TerrainKinds, BoundaryIsClosedAndFreeSpaceIsConnected) {
  const TerrainGenerator generator =
      *TerrainGenerator::Create({.kind = GetParam(), .size = 20.0, .seed = 3});
  const Terrain terrain = generator.Generate();
  const grid::OccupancyGrid truth = *RasterizeTerrain(terrain, 0.05);
  ASSERT_EQ(truth.width(), 400);
  for (int i = 0; i < truth.width(); ++i) {
    EXPECT_EQ(truth.at(i, 0), grid::kOccupiedValue);
    EXPECT_EQ(truth.at(0, i), grid::kOccupiedValue);
    EXPECT_EQ(truth.at(i, truth.height() - 1), grid::kOccupiedValue);
    EXPECT_EQ(truth.at(truth.width() - 1, i), grid::kOccupiedValue);
  }
  const grid::StateCounts counts = truth.CountStates();
  EXPECT_EQ(counts.unknown, 0);
  // Every free cell is reachable from the start (office rooms through their doors), apart from a
  // few cells trapped in the corners where walls meet furniture or each other.
  const int64_t reachable = ReachableFree(truth, terrain.start.translation());
  EXPECT_GE(reachable, counts.free * 99 / 100) << reachable << " of " << counts.free;
}

INSTANTIATE_TEST_SUITE_P(All, TerrainKinds,
                         ::testing::Values(TerrainKind::kMaze, TerrainKind::kOffice,
                                           TerrainKind::kUnstructured, TerrainKind::kWarehouse));

TEST(TerrainGeneratorTest, OfficeHasRoomsWithDoors) {
  const Terrain terrain =
      TerrainGenerator::Create({.kind = TerrainKind::kOffice, .size = 40.0, .seed = 1})->Generate();
  EXPECT_GT(terrain.doors.size(), 10u);
  EXPECT_GT(terrain.polygons.size(), 5u);
  for (const Door& door : terrain.doors) EXPECT_TRUE(door.open);
}

TEST(TerrainGeneratorTest, WarehouseRacksRepeatAtOnePeriod) {
  const Terrain terrain =
      TerrainGenerator::Create({.kind = TerrainKind::kWarehouse, .size = 40.0, .seed = 2})
          ->Generate();
  // The racks: furniture boxes starting at the west side aisle, one per row (the cross aisle
  // splits each row in two; the east halves and the pallets start further east).
  std::vector<double> rows;
  double west = 1e9;
  for (const SolidPolygon& box : terrain.polygons) {
    if (box.kind == ObstacleKind::kFurniture) west = std::min(west, box.points[0].x());
  }
  for (const SolidPolygon& box : terrain.polygons) {
    if (box.kind == ObstacleKind::kFurniture && box.points[0].x() == west) {
      rows.push_back(box.points[0].y());
    }
  }
  std::sort(rows.begin(), rows.end());
  ASSERT_GE(rows.size(), 8u) << "a 40 m warehouse holds rows of racks every 3-3.8 m";
  const double period = rows[1] - rows[0];
  EXPECT_GE(period, 3.0);
  EXPECT_LE(period, 3.8);
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_NEAR(rows[i] - rows[i - 1], period, 1e-9);
  EXPECT_EQ(TerrainKindName(terrain.kind), "warehouse");
}

TEST(TerrainGeneratorTest, RefusesBadOptionsNamingThem) {
  const StatusOr<TerrainGenerator> zero = TerrainGenerator::Create({.size = 0.0});
  ASSERT_FALSE(zero.ok());
  EXPECT_NE(zero.status().message().find("size"), std::string::npos);
  EXPECT_FALSE(TerrainGenerator::Create({.size = kMaxTerrainSize + 1.0}).ok());
  EXPECT_FALSE(TerrainGenerator::Create({.size = 10.0, .wall_thickness = 0.0}).ok());
  const Terrain terrain = TerrainGenerator::Create({})->Generate();
  const StatusOr<grid::OccupancyGrid> bad = RasterizeTerrain(terrain, 0.0);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("resolution"), std::string::npos);
}

TEST(TerrainGeneratorTest, KindNamesRoundTrip) {
  for (TerrainKind kind : {TerrainKind::kMaze, TerrainKind::kOffice, TerrainKind::kUnstructured,
                           TerrainKind::kWarehouse}) {
    EXPECT_EQ(TerrainKindFromName(TerrainKindName(kind)), kind);
  }
  EXPECT_FALSE(TerrainKindFromName("cave").has_value());
}

}  // namespace
}  // namespace fleetmap::sim
