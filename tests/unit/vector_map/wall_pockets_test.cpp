#include "common/vector_map/wall_pockets.hpp"

#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::vector_map {
namespace {

using Cells = std::set<std::pair<int, int>>;

Cells PocketsOf(const grid::OccupancyGrid& grid, const CellRect& rect) {
  CellRaster raster(grid, rect, 4, {});
  Cells cells;
  for (const int i : WallPocketCells(raster)) cells.insert({raster.X(i), raster.Y(i)});
  for (int y = rect.y0 - 4; y < rect.y0 + rect.height + 4; ++y) {
    for (int x = rect.x0 - 4; x < rect.x0 + rect.width + 4; ++x) {
      EXPECT_FALSE(raster.Has(raster.Index(x, y), CellRaster::kVisited)) << x << "," << y;
    }
  }
  return cells;
}

// A wall four cells thick (rows 1-4) whose row 3 holds, from left to right: a one-cell unknown
// pocket (x 2), a two-cell one (x 5-6), a three-cell slit (x 10-12, too long), a one-cell free
// pocket (x 15), a cell open to the free space above through a gap in the face (x 18) and the top
// of a 2 x 2 hole (x 23-24, rows 2-3: not a slit).
const std::vector<std::string> kWall = {
    ".............................", "##################.#########.",
    "##?##??###???##.##?####??###.", "#######################??###.",
    "#############################", ".............................",
};

TEST(WallPocketsTest, FindsOnlyEnclosedSlitsOfOneOrTwoCells) {
  const grid::OccupancyGrid grid = testing::GridFromPicture(kWall);
  const Cells expected = {{2, 3}, {5, 3}, {6, 3}, {15, 3}};
  EXPECT_EQ(PocketsOf(grid, CellRect{0, 0, grid.width(), grid.height()}), expected);
}

TEST(WallPocketsTest, APocketJustOutsideTheRectangleIsReportedForItsAnchors) {
  const grid::OccupancyGrid grid = testing::GridFromPicture(kWall);
  // Columns 0-4: the pocket at x 5-6 lies in the rectangle grown by one (x 5) and beyond it.
  const Cells near = PocketsOf(grid, CellRect{0, 0, 5, grid.height()});
  EXPECT_EQ(near, (Cells{{2, 3}, {5, 3}}));
  // Columns 0-3: x 5 is two cells away, so only the pocket inside is reported.
  EXPECT_EQ(PocketsOf(grid, CellRect{0, 0, 4, grid.height()}), (Cells{{2, 3}}));
}

TEST(WallPocketsTest, NothingInOpenSpaceOrAnEmptyGrid) {
  const grid::OccupancyGrid free_grid(20, 10, 0.05, {}, grid::kFreeValue);
  EXPECT_TRUE(PocketsOf(free_grid, CellRect{0, 0, 20, 10}).empty());
  grid::OccupancyGrid room(20, 10, 0.05, {}, grid::kFreeValue);
  testing::FillRect(room, 0, 0, 19, 0, grid::kOccupiedValue);
  testing::FillRect(room, 0, 9, 19, 9, grid::kOccupiedValue);
  testing::FillRect(room, 0, 0, 0, 9, grid::kOccupiedValue);
  testing::FillRect(room, 19, 0, 19, 9, grid::kOccupiedValue);
  EXPECT_TRUE(PocketsOf(room, CellRect{0, 0, 20, 10}).empty());  // a room is not a pocket
}

}  // namespace
}  // namespace fleetmap::vector_map
