#include "common/vector_map/cell_raster.hpp"

#include <gtest/gtest.h>

#include "common/vector_map/delimitation.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

TEST(CellRasterTest, DelimitationMatchesTheReferenceOnNoiseAndTiles) {
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const grid::OccupancyGrid grid = testing::NoiseGrid(53, 41, 0.4, seed);
    for (const CellRect rect : {CellRect{0, 0, 53, 41}, CellRect{16, 8, 16, 16}}) {
      const CellRaster raster(grid, rect, 4, {});
      const Delimitation reference(grid, rect, 4, {});
      int owned = 0;
      for (int y = rect.y0 - 4; y < rect.y0 + rect.height + 4; ++y) {
        for (int x = rect.x0 - 4; x < rect.x0 + rect.width + 4; ++x) {
          ASSERT_EQ(raster.IsDelimitation(x, y), reference.IsDelimitation(x, y)) << x << "," << y;
          ASSERT_EQ(raster.Has(raster.Index(x, y), CellRaster::kOccupied),
                    reference.Occupied(x, y));
          owned += rect.Contains(x, y) && reference.IsDelimitation(x, y);
        }
      }
      EXPECT_EQ(static_cast<int>(raster.owned_delimitation().size()), owned);
    }
  }
}

TEST(CellRasterTest, OccupiedListCoversTheRectangleGrownByOne) {
  const grid::OccupancyGrid grid(10, 10, 0.05, {}, grid::kOccupiedValue);
  const CellRaster raster(grid, CellRect{2, 2, 3, 3}, 2, {});
  EXPECT_EQ(raster.occupied_near_rect().size(), 25u);
  EXPECT_TRUE(raster.owned_delimitation().empty());  // all interior
}

}  // namespace
}  // namespace fleetmap::vector_map
