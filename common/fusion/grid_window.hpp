#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/core/ids.hpp"

namespace fleetmap::fusion {

// A rectangle of tiles, both corners included.
struct TileRect {
  TileId min;
  TileId max;

  int64_t width() const { return int64_t{max.x} - min.x + 1; }
  int64_t height() const { return int64_t{max.y} - min.y + 1; }
  int64_t area() const { return width() * height(); }
  bool Contains(const TileId& tile) const {
    return tile.x >= min.x && tile.x <= max.x && tile.y >= min.y && tile.y <= max.y;
  }
};

// Which tiles one dense grid shows, and how many it leaves out.
struct GridWindow {
  TileRect rect;
  size_t tiles_shown = 0;
  size_t tiles_left_out = 0;
};

// A fused tile, the robots (any small ids) that contributed to it, and when it first appeared
// (any increasing count).
struct SourcedTile {
  TileId tile;
  std::vector<int> robots;
  uint64_t first_seen = 0;
};

// Chooses the rectangle of tiles a dense grid (rt/fleetmap/map) can show with at most
// `max_tiles` tiles of area. A fleet's tiles usually fit, and then all are shown. When they span
// more (robots kilometres apart, or a peer's tiles far away) the grid shows one group of nearby
// tiles (tiles at most `gap` empty tiles apart belong to one group): the one that appeared first,
// then the one most robots mapped, so that tiles sent from far away later, however many and by
// however many robot ids, cannot take the view from the fleet. It is cut around its median tile
// if even the group is too large. Memory and time follow
// the number of tiles, never their bounding box. `tiles` must not be empty; max_tiles >= 1.
GridWindow ChooseGridWindow(const std::vector<SourcedTile>& tiles, int64_t max_tiles, int gap = 2);

}  // namespace fleetmap::fusion
