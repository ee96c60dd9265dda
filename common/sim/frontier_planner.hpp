#pragma once

// Frontier-based exploration (Yamauchi 1997) on the robot's own map. The planner looks at the map
// in square blocks (OccupancyMapper keeps per-block counts, block_size cells a side, ~20 cm):
// a block is occupied if any of its cells is, free if at least half of its cells are free, unknown
// otherwise. A frontier block is a free block with an unknown 4-neighbour; isolated frontier
// blocks (fewer than `min_frontier_blocks` in their 3 x 3 neighbourhood) are ignored. Blocks
// within `inflation_radius` of an occupied block are not traversable. A breadth-first search from
// the robot's block over traversable blocks (8-connected) finds the nearest traversable block
// within two blocks of a frontier that is not blacklisted; the path to it is shortened by
// line-of-sight (string pulling) so the robot drives few, long straight legs.
//
// Thread-safety: not thread-safe; one owner.

#include <cstdint>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/sim/occupancy_mapper.hpp"

namespace fleetmap::sim {

struct FrontierOptions {
  double inflation_radius = 0.3;  // metres, > 0: clearance the planner keeps from obstacles
  double blacklist_radius = 1.0;  // metres, >= 0: around a goal reached or given up
  int min_frontier_blocks = 2;    // >= 1
};

class FrontierPlanner {
 public:
  // Errors (kInvalidArgument) name the option.
  static StatusOr<FrontierPlanner> Create(const FrontierOptions& options);

  // The path (map-frame points, first the robot's own position) to the nearest frontier goal, or
  // an empty path when no reachable frontier is left.
  std::vector<Point2> Plan(const OccupancyMapper& map, const Point2& robot);
  // No goal within blacklist_radius of `goal` will be chosen again.
  void Blacklist(const OccupancyMapper& map, const Point2& goal);

 private:
  explicit FrontierPlanner(const FrontierOptions& options) : options_(options) {}

  enum : uint8_t { kUnknownBlock = 0, kFreeBlock = 1, kOccupiedBlock = 2 };

  void Classify(const OccupancyMapper& map);
  bool LineOfSight(int x0, int y0, int x1, int y1) const;
  bool Passable(size_t index) const { return traversable_[index] || start_region_[index]; }

  FrontierOptions options_;
  int bw_ = 0;
  int bh_ = 0;
  double block_m_ = 0.0;
  std::vector<uint8_t> state_;
  std::vector<uint8_t> traversable_;
  std::vector<uint8_t> near_frontier_;
  std::vector<uint8_t> start_region_;
  std::vector<uint8_t> blacklist_;
};

}  // namespace fleetmap::sim
