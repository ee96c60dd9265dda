#include "server/patched_grid.hpp"

#include <gtest/gtest.h>

#include <string>

namespace fleetmap::server {
namespace {

using std::chrono::seconds;

const Timestamp kMapStamp = Timestamp{} + seconds(100);

transport::MapMessage WholeMap() {
  transport::MapMessage map;
  map.grid = grid::OccupancyGrid(6, 4, 0.05, Pose2{}, grid::kUnknownValue);
  map.stamp = kMapStamp;
  return map;
}

transport::MapUpdate Update(int x, int y, int width, int height, int8_t value,
                            Timestamp stamp = kMapStamp + seconds(1)) {
  transport::MapUpdate update;
  update.x = x;
  update.y = y;
  update.width = width;
  update.height = height;
  update.data.assign(static_cast<size_t>(width) * height, value);
  update.stamp = stamp;
  return update;
}

TEST(PatchedGridTest, RefusesAnUpdateBeforeAnyWholeMap) {
  PatchedGrid grid;
  const auto outcome = grid.Apply(Update(0, 0, 2, 2, 0));
  ASSERT_FALSE(outcome.ok());
  EXPECT_NE(outcome.status().message().find("before any whole map"), std::string::npos);
  EXPECT_FALSE(grid.map().has_value());
}

TEST(PatchedGridTest, AppliesUpdatesAndDatesTheGridByTheNewest) {
  PatchedGrid grid;
  grid.Replace(WholeMap());
  const auto outcome = grid.Apply(Update(1, 1, 2, 2, grid::kOccupiedValue));
  ASSERT_TRUE(outcome.ok()) << outcome.status();
  EXPECT_EQ(*outcome, PatchedGrid::Outcome::kApplied);
  EXPECT_EQ(grid.map()->grid.at(2, 2), grid::kOccupiedValue);
  EXPECT_EQ(grid.map()->grid.at(0, 0), grid::kUnknownValue);
  EXPECT_EQ(grid.map()->stamp, kMapStamp + seconds(1));
}

TEST(PatchedGridTest, RefusesUpdatesOutsideTheMapOrOfTheWrongLengthAndKeepsTheGrid) {
  PatchedGrid grid;
  grid.Replace(WholeMap());
  const grid::OccupancyGrid before = grid.map()->grid;
  const auto outside = grid.Apply(Update(5, 3, 2, 2, 0));
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.status().message().find("outside the 6 x 4 map"), std::string::npos);
  transport::MapUpdate short_update = Update(0, 0, 2, 2, 0);
  short_update.data.pop_back();
  const auto short_one = grid.Apply(short_update);
  ASSERT_FALSE(short_one.ok());
  EXPECT_NE(short_one.status().message().find("2 x 2 cells carries 3"), std::string::npos);
  EXPECT_EQ(grid.map()->grid, before);
}

TEST(PatchedGridTest, SkipsUpdatesOlderThanTheWholeMap) {
  PatchedGrid grid;
  grid.Replace(WholeMap());
  const auto outcome = grid.Apply(Update(0, 0, 1, 1, 0, kMapStamp - seconds(1)));
  ASSERT_TRUE(outcome.ok());
  EXPECT_EQ(*outcome, PatchedGrid::Outcome::kStale);
  EXPECT_EQ(grid.map()->grid.at(0, 0), grid::kUnknownValue);
}

TEST(PatchedGridTest, InflatesCompressedUpdatesWithinTheMapOnly) {
  PatchedGrid grid;
  grid.Replace(WholeMap());
  auto compressed = transport::CompressMapUpdate(Update(2, 0, 3, 2, grid::kFreeValue), 3);
  ASSERT_TRUE(compressed.ok());
  ASSERT_TRUE(grid.Apply(*compressed).ok());
  EXPECT_EQ(grid.map()->grid.at(4, 1), grid::kFreeValue);

  // A lying raw_size, and a patch that claims a rectangle beyond the map: refused, nothing
  // allocated for them, the grid unchanged.
  const grid::OccupancyGrid before = grid.map()->grid;
  transport::CompressedMapUpdate lying = *compressed;
  lying.raw_size = 3'000'000'000u;
  const auto lie = grid.Apply(lying);
  ASSERT_FALSE(lie.ok());
  EXPECT_NE(lie.status().message().find("raw_size 3000000000"), std::string::npos);
  transport::CompressedMapUpdate outside = *compressed;
  outside.x = 1'000'000;
  EXPECT_FALSE(grid.Apply(outside).ok());
  transport::CompressedMapUpdate corrupt = *compressed;
  corrupt.data.assign(corrupt.data.size(), 0x5a);
  EXPECT_FALSE(grid.Apply(corrupt).ok());
  EXPECT_EQ(grid.map()->grid, before);
}

}  // namespace
}  // namespace fleetmap::server
