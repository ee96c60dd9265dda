#pragma once

// How a robot's map travels to the server: what an agent puts on the wire (--wire), and what the
// server follows (a robot's status names the topic). docs/fleet.md compares them.

#include <optional>
#include <string>
#include <string_view>

namespace fleetmap {

enum class Wire {
  kTiles,            // vector tiles on rt/fleetmap/robot_tiles: the product
  kGrid,             // the whole nav_msgs/OccupancyGrid on rt/<robot>/map at every change
  kGridUpdates,      // the whole grid once, then map_msgs/OccupancyGridUpdate per changed tile
  kGridUpdatesZstd,  // the same patches, zstd -3, as fleetmap_msgs/CompressedGridUpdate
};

inline const char* WireName(Wire wire) {
  switch (wire) {
    case Wire::kTiles:
      return "tiles";
    case Wire::kGrid:
      return "grid";
    case Wire::kGridUpdates:
      return "grid-updates";
    case Wire::kGridUpdatesZstd:
      return "grid-updates-zstd";
  }
  return "unknown";
}

inline std::optional<Wire> WireFromName(std::string_view name) {
  for (const Wire wire : {Wire::kTiles, Wire::kGrid, Wire::kGridUpdates, Wire::kGridUpdatesZstd}) {
    if (name == WireName(wire)) return wire;
  }
  return std::nullopt;
}

}  // namespace fleetmap
