#pragma once

// Grids for the vector-map tests: ASCII pictures and the real maps of ../shared/data/maps (in a
// lone clone, the three of them copied into tests/data/maps/real).

#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/grid/map_io.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/rasterizer.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map::testing {

// '#' occupied, '.' free, anything else unknown. The first string is the TOP row (largest y).
inline grid::OccupancyGrid GridFromPicture(const std::vector<std::string>& rows,
                                           double resolution = 0.05, Pose2 origin = {}) {
  const int height = static_cast<int>(rows.size());
  const int width = height == 0 ? 0 : static_cast<int>(rows[0].size());
  grid::OccupancyGrid grid(width, height, resolution, origin);
  for (int r = 0; r < height; ++r) {
    for (int x = 0; x < width; ++x) {
      const char c = rows[r][x];
      grid.at(x, height - 1 - r) =
          c == '#' ? grid::kOccupiedValue : (c == '.' ? grid::kFreeValue : grid::kUnknownValue);
    }
  }
  return grid;
}

// Fills the rectangle [x0, x1] x [y0, y1] (inclusive) with `value`.
inline void FillRect(grid::OccupancyGrid& grid, int x0, int y0, int x1, int y1, int8_t value) {
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (grid.Contains(x, y)) grid.at(x, y) = value;
    }
  }
}

// A thick line of occupied cells: cells whose centre lies within half_width of segment a-b.
inline void DrawLine(grid::OccupancyGrid& grid, double ax, double ay, double bx, double by,
                     double half_width) {
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const double dx = bx - ax, dy = by - ay;
      const double len2 = dx * dx + dy * dy;
      double t = len2 > 0 ? ((x - ax) * dx + (y - ay) * dy) / len2 : 0.0;
      t = t < 0 ? 0 : (t > 1 ? 1 : t);
      const double ex = ax + t * dx - x, ey = ay + t * dy - y;
      if (ex * ex + ey * ey <= half_width * half_width) grid.at(x, y) = grid::kOccupiedValue;
    }
  }
}

// Random grid: each cell occupied with probability p_occupied, else free or unknown.
inline grid::OccupancyGrid NoiseGrid(int width, int height, double p_occupied, uint32_t seed) {
  grid::OccupancyGrid grid(width, height, 0.05);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (auto& v : grid.mutable_data()) {
    const double s = u(rng);
    v = s < p_occupied ? grid::kOccupiedValue : (s < 0.8 ? grid::kFreeValue : grid::kUnknownValue);
  }
  return grid;
}

// A synthetic floor plan: rooms with walls 1 to 4 cells thick, a diagonal wall, a pillar, speckle.
inline grid::OccupancyGrid FloorPlan() {
  grid::OccupancyGrid grid(120, 90, 0.05);
  FillRect(grid, 0, 0, 119, 89, grid::kFreeValue);
  FillRect(grid, 2, 2, 117, 3, grid::kOccupiedValue);     // 2 thick
  FillRect(grid, 2, 86, 117, 86, grid::kOccupiedValue);   // 1 thick
  FillRect(grid, 2, 2, 4, 86, grid::kOccupiedValue);      // 3 thick
  FillRect(grid, 114, 2, 117, 86, grid::kOccupiedValue);  // 4 thick
  FillRect(grid, 60, 2, 61, 50, grid::kOccupiedValue);
  DrawLine(grid, 62, 50, 100, 80, 0.8);
  FillRect(grid, 20, 30, 34, 44, grid::kOccupiedValue);  // solid blob
  grid.at(45, 70) = grid::kOccupiedValue;                // speckle
  grid.at(47, 71) = grid::kOccupiedValue;
  FillRect(grid, 80, 10, 100, 20, grid::kUnknownValue);
  return grid;
}

// Cells `grid` calls occupied that `back` calls free: each would tell a planner it can drive
// through an obstacle. A round trip must leave none.
inline int OccupiedComeBackFree(const grid::OccupancyGrid& grid, const grid::OccupancyGrid& back) {
  int count = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      count += grid.StateAt(x, y) == grid::CellState::kOccupied &&
                       back.StateAt(x, y) == grid::CellState::kFree
                   ? 1
                   : 0;
    }
  }
  return count;
}

// Cells `grid` calls occupied that `back` calls free although no obstacle edge of `map` passes
// within epsilon of them: obstacles the vector map lost. A round trip must leave none; occupied
// cells within epsilon of an edge are stood for by it (the epsilon-error constraint's bound) and
// may come back free. `back` gives the geometry (it may be in another frame than `grid`).
inline int OccupiedFarFromObstaclesComeBackFree(const grid::OccupancyGrid& grid,
                                                const vector_map::VectorMap& map,
                                                const grid::OccupancyGrid& back) {
  vector_map::VectorMap obstacles = map;
  obstacles.free_space.clear();
  vector_map::RasterizerOptions within_epsilon;
  within_epsilon.use_half_width = false;
  within_epsilon.occupied_radius = map.epsilon;
  const grid::OccupancyGrid near =
      *vector_map::Rasterizer(within_epsilon).Rasterize(obstacles, back);
  int count = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      count += grid.StateAt(x, y) == grid::CellState::kOccupied &&
                       back.StateAt(x, y) == grid::CellState::kFree &&
                       near.StateAt(x, y) != grid::CellState::kOccupied
                   ? 1
                   : 0;
    }
  }
  return count;
}

// Cells `grid` calls occupied that `back` does not: with `back` rasterized from obstacles only,
// the occupied cells the obstacles leave unpainted (each costs the free space a hole or a notch
// and comes back unknown).
inline int OccupiedLeftUnpainted(const grid::OccupancyGrid& grid, const grid::OccupancyGrid& back) {
  int count = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      count += grid.StateAt(x, y) == grid::CellState::kOccupied &&
                       back.StateAt(x, y) != grid::CellState::kOccupied
                   ? 1
                   : 0;
    }
  }
  return count;
}

// A small vector map with every kind of element: an open polyline with a half width, a closed
// one, a point obstacle, and a free polygon with a hole (for the picture and export tests).
inline VectorMap SmallVectorMap() {
  VectorMap map;
  map.epsilon = 0.07;
  map.resolution = 0.05;
  map.obstacles.push_back(Polyline{{Point2(0, 0), Point2(1, 0), Point2(1, 1)}, false, 0.035});
  map.obstacles.push_back(Polyline{{Point2(2, 2), Point2(3, 2), Point2(3, 3)}, true});
  map.obstacles.push_back(Polyline{{Point2(5, 5)}});
  map.free_space.push_back(FreePolygon{{Point2(0, 0), Point2(4, 0), Point2(4, 4), Point2(0, 4)},
                                       {{Point2(1, 1), Point2(2, 1), Point2(2, 2)}}});
  return map;
}

// The real maps of ../shared/data/maps (SOURCES.md); those absent from FLEETMAP_SHARED_MAPS_DIR
// (in a lone clone all but tb3_world, strands_kth and aws_small_house) are skipped.
inline const std::vector<std::string>& RealMapNames() {
  static const std::vector<std::string> names = {
      "intel_lab",   "aces3_austin",    "nav2_warehouse", "willow_garage_2010",
      "strands_kth", "aws_small_house", "tb3_world"};
  return names;
}

// Loads a real map with grid::LoadMap; false if the maps directory or the map is absent.
inline bool LoadRealMap(const std::string& name, grid::OccupancyGrid& out) {
  auto loaded = grid::LoadMap(std::string(FLEETMAP_SHARED_MAPS_DIR) + "/" + name + ".yaml");
  if (!loaded.ok()) return false;
  out = std::move(loaded->grid);
  return true;
}

}  // namespace fleetmap::vector_map::testing
