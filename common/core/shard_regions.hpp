#pragma once

// Shards: the fleet map cut by region over several servers (docs/shards.md). A shard owns the
// fleet tiles whose centre lies in its region, a rectangle in metres of the fleet frame, so
// regions that do not overlap own disjoint tiles whatever the tile size, and a region's border
// may fall inside a tile (that tile goes to the shard holding its centre).

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"

namespace fleetmap {

// Inclusive ranges of tile indices: the tiles (x, y) with min_x <= x <= max_x and
// min_y <= y <= max_y. Empty when a minimum exceeds its maximum.
struct TileBox {
  int32_t min_x = 0;
  int32_t min_y = 0;
  int32_t max_x = -1;
  int32_t max_y = -1;

  bool empty() const { return min_x > max_x || min_y > max_y; }
  bool Contains(const TileId& tile) const {
    return tile.x >= min_x && tile.x <= max_x && tile.y >= min_y && tile.y <= max_y;
  }
  friend bool operator==(const TileBox&, const TileBox&) = default;
};

struct ShardRegion {
  std::string name;  // a ROS 2 name token: the shard's map is rt/fleetmap/<name>/map
  double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;  // metres, fleet frame

  // The tiles of `tile_size` metres whose centre lies in [min_x, max_x) x [min_y, max_y).
  TileBox Tiles(double tile_size) const;
};

// Every shard of a fleet, in the order they were listed.
class ShardPlan {
 public:
  // Errors name the shard: a name that is not a ROS name token or is listed twice, a region
  // that is not finite or has no area, two regions that overlap, a robot homed on a shard that
  // is not listed. `homes`: the shard that places each robot at an unknown pose (robots not
  // listed: the first shard).
  static StatusOr<ShardPlan> Create(std::vector<ShardRegion> regions,
                                    std::map<RobotId, std::string> homes = {});

  const std::vector<ShardRegion>& regions() const { return regions_; }
  const ShardRegion* Find(const std::string& name) const;
  // The shard owning `tile` (nullptr: the tile lies on no shard's region).
  const ShardRegion* OwnerOf(const TileId& tile, double tile_size) const;
  // The shard that places `robot` when its frame is not known (its home): the other shards
  // follow its placement (docs/shards.md).
  const std::string& HomeOf(const RobotId& robot) const;

 private:
  std::vector<ShardRegion> regions_;
  std::map<RobotId, std::string> homes_;
};

// The shard one server runs: its own region and the plan it belongs to (tiles on no shard's
// region are reported only when the plan lists the others).
struct ShardAssignment {
  ShardPlan plan;
  std::string name;

  const ShardRegion& region() const { return *plan.Find(name); }
  // Whether this shard places `robot` when its frame is not known.
  bool IsHomeOf(const RobotId& robot) const { return plan.HomeOf(robot) == name; }
};

}  // namespace fleetmap
