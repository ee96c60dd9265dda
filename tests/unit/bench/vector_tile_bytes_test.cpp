#include "bench/bytes/vector_tile_bytes.hpp"

#include <gtest/gtest.h>

#include "bench/bytes/grid_tile_bytes.hpp"
#include "common/transport/tile_payload.hpp"

namespace fleetmap::bench {
namespace {

// 20 m x 10 m at 0.05 m: a free room with walls in fleet tile (0, 0), tile (1, 0) unknown.
grid::OccupancyGrid Room() {
  grid::OccupancyGrid grid(400, 200, 0.05);
  for (int y = 20; y < 180; ++y) {
    for (int x = 20; x < 180; ++x) {
      const bool wall = x == 20 || x == 179 || y == 20 || y == 179;
      grid.at(x, y) = wall ? grid::kOccupiedValue : grid::kFreeValue;
    }
  }
  return grid;
}

vector_map::TiledVectorMap Vectorized(const grid::OccupancyGrid& grid) {
  StatusOr<vector_map::TiledVectorMap> map =
      vector_map::VectorizeTiled(grid, Transform2::Identity());
  EXPECT_TRUE(map.ok()) << map.status();
  return std::move(map).value();
}

TEST(VectorTileBytesTest, CountsEachTileAsTheSampleOnTheRobotTilesTopic) {
  const vector_map::TiledVectorMap map = Vectorized(Room());
  const StatusOr<VectorTileBytes> bytes = MeasureVectorTileBytes(map);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  ASSERT_EQ(bytes->tiles, 1u);
  transport::VectorTileMessage message;
  message.robot_id = kBenchRobot;
  message.tile = {0, 0};
  message.revision = 1;
  message.tile_size = map.tile_size;
  message.map = map.tiles.at({0, 0});
  const StatusOr<std::string> payload = transport::EncodeTilePayload(message);
  ASSERT_TRUE(payload.ok()) << payload.status();
  EXPECT_EQ(bytes->payload, payload->size());
}

TEST(VectorTileBytesTest, ComparesTheSameTilesAsTheGridBaselines) {
  const grid::OccupancyGrid grid = Room();
  const StatusOr<VectorTileBytes> vector = MeasureVectorTileBytes(Vectorized(grid));
  const StatusOr<TiledGridBytes> baselines =
      MeasureTiledGridBytes(grid, Transform2::Identity(), 10.0);
  ASSERT_TRUE(vector.ok() && baselines.ok());
  EXPECT_EQ(vector->tiles, baselines->tiles);
}

TEST(VectorTileBytesTest, TheRobotIdTravelsInEverySample) {
  const vector_map::TiledVectorMap map = Vectorized(Room());
  const StatusOr<VectorTileBytes> short_id = MeasureVectorTileBytes(map, RobotId{"r"});
  const StatusOr<VectorTileBytes> long_id =
      MeasureVectorTileBytes(map, RobotId{"a_rather_long_robot_name"});
  ASSERT_TRUE(short_id.ok() && long_id.ok());
  EXPECT_GT(long_id->payload, short_id->payload);
}

TEST(VectorTileBytesTest, AnEmptyMapCostsNothing) {
  const StatusOr<VectorTileBytes> bytes = MeasureVectorTileBytes(vector_map::TiledVectorMap{});
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(bytes->tiles, 0u);
  EXPECT_EQ(bytes->payload, 0u);
}

}  // namespace
}  // namespace fleetmap::bench
