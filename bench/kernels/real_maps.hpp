#pragma once

// The real maps the kernels run on (../shared/data/maps, SOURCES.md), each loaded once per
// process. FLEETMAP_SHARED_MAPS_DIR is set by bench/kernels/CMakeLists.txt.

#include <map>
#include <string>
#include <vector>

#include "common/grid/map_io.hpp"

namespace fleetmap::bench {

inline const std::vector<std::string>& RealMapNames() {
  static const std::vector<std::string> names = {
      "intel_lab",   "aces3_austin",    "nav2_warehouse", "willow_garage_2010",
      "strands_kth", "aws_small_house", "tb3_world"};
  return names;
}

// Null if the map is absent (a clone without ../shared): the kernel then skips it.
inline const grid::OccupancyGrid* LoadRealMap(const std::string& name) {
  static std::map<std::string, grid::OccupancyGrid> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    auto loaded = grid::LoadMap(std::string(FLEETMAP_SHARED_MAPS_DIR) + "/" + name + ".yaml");
    if (!loaded.ok()) return nullptr;
    it = cache.emplace(name, std::move(loaded->grid)).first;
  }
  return &it->second;
}

}  // namespace fleetmap::bench
