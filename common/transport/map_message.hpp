#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::transport {

// A grid as it travels in a nav_msgs/OccupancyGrid: the grid, its frame and time.
struct MapMessage {
  grid::OccupancyGrid grid;
  std::string frame_id = "map";
  Timestamp stamp;
  size_t serialized_bytes = 0;  // CDR payload size, set by readers and writers
};

// A map_msgs/OccupancyGridUpdate: new values for the cells [x, x + width) x [y, y + height) of
// the last full map on the matching map topic, row-major.
struct MapUpdate {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
  std::vector<int8_t> data;
  Timestamp stamp;
  std::string frame_id = "map";
  size_t serialized_bytes = 0;  // payload size, set by readers
};

// Fails (kInvalidArgument, naming the rectangle) when the rectangle of `update` does not lie
// inside a map of `map_width` x `map_height` cells: what ApplyMapUpdate checks first, for callers
// that must judge a rectangle before its cells exist (a compressed update).
Status CheckUpdateRectangle(int x, int y, int width, int height, int map_width, int map_height);

// Writes `update` into `map`. Fails (kInvalidArgument, naming the rectangle) when the rectangle
// does not lie inside the map; `map` is unchanged then.
Status ApplyMapUpdate(const MapUpdate& update, grid::OccupancyGrid* map);

}  // namespace fleetmap::transport
