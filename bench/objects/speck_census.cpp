#include "bench/objects/speck_census.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fleetmap::bench {

SpeckCensus CountLoneSpecks(const grid::OccupancyGrid& map, const SpeckCensusOptions& options) {
  SpeckCensus census;
  const int width = map.width(), height = map.height();
  const double cell_area = map.resolution() * map.resolution();
  std::vector<uint8_t> occupied(static_cast<size_t>(width) * height, 0);
  std::vector<uint8_t> free(occupied.size(), 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const grid::CellState state = map.StateAt(x, y);
      const size_t i = static_cast<size_t>(y) * width + x;
      occupied[i] = state == grid::CellState::kOccupied;
      free[i] = state == grid::CellState::kFree;
      census.free_area_m2 += free[i] * cell_area;
    }
  }
  const int radius =
      std::max(1, static_cast<int>(std::ceil(options.isolation_m / map.resolution())));
  // Component labels: 0 not yet visited; every occupied cell gets its component's number.
  std::vector<int32_t> label(occupied.size(), 0);
  int32_t next = 0;
  std::vector<grid::CellIndex> cells, stack;
  for (int sy = 0; sy < height; ++sy) {
    for (int sx = 0; sx < width; ++sx) {
      const size_t start = static_cast<size_t>(sy) * width + sx;
      if (!occupied[start] || label[start] != 0) continue;
      label[start] = ++next;
      cells.clear();
      stack.assign(1, {sx, sy});
      while (!stack.empty()) {  // the whole component, however large, so it is visited once
        const grid::CellIndex c = stack.back();
        stack.pop_back();
        cells.push_back(c);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = c.x + dx, y = c.y + dy;
            if (!map.Contains(x, y)) continue;
            const size_t j = static_cast<size_t>(y) * width + x;
            if (occupied[j] && label[j] == 0) {
              label[j] = next;
              stack.push_back({x, y});
            }
          }
        }
      }
      const int n = static_cast<int>(cells.size());
      if (n > options.max_cells) continue;
      int x0 = sx, x1 = sx, y0 = sy, y1 = sy;
      for (const grid::CellIndex& c : cells) {
        x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
        y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
      }
      bool alone = true;
      int around = 0, known_free = 0;
      for (int y = y0 - radius; y <= y1 + radius && alone; ++y) {
        for (int x = x0 - radius; x <= x1 + radius; ++x) {
          if (!map.Contains(x, y)) {
            ++around;  // off the map: not known free
            continue;
          }
          const size_t j = static_cast<size_t>(y) * width + x;
          if (label[j] == next) continue;
          if (occupied[j]) {
            alone = false;
            break;
          }
          ++around;
          known_free += free[j];
        }
      }
      if (!alone || 4 * known_free < 3 * around) continue;
      if (n <= 3) {
        ++census.lone_specks;
        continue;
      }
      ++census.lone_clusters;
      const int w = x1 - x0 + 1, h = y1 - y0 + 1;
      census.lone_compact += n <= 7 && w <= 3 && h <= 3 && 2 * n >= w * h;
    }
  }
  return census;
}

}  // namespace fleetmap::bench
