#pragma once

#include <cstddef>
#include <string>

#include "common/core/robot_status.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::transport {

// A grid as it travels in a nav_msgs/OccupancyGrid: the grid, its frame and time.
struct MapMessage {
  grid::OccupancyGrid grid;
  std::string frame_id = "map";
  Timestamp stamp;
  size_t serialized_bytes = 0;  // CDR payload size, set by readers and writers
};

}  // namespace fleetmap::transport
