#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <set>

#include "common/core/ids.hpp"
#include "common/core/shard_regions.hpp"
#include "common/transport/tile_region_selection.hpp"

namespace fleetmap::server {

// What a shard's server reads of rt/fleetmap/robot_tiles by region (docs/shards.md), and what it
// says of the tiles no shard fuses. It reads its own tiles and the tiles on no shard's region,
// which it reports once a minute per robot; the other shards' tiles reach it only from writers
// that do not filter (another vendor's), and are dropped quietly. (The tiles of robots that send
// in their own map frame it reads whole, robot by robot: TileIntake.) DDS-free; not
// thread-safe: the fusion worker's.
class ShardTileScope {
 public:
  ShardTileScope(ShardAssignment shard, double tile_size);

  const ShardAssignment& shard() const { return shard_; }
  const TileBox& own_tiles() const { return own_; }
  bool Owns(const TileId& tile) const { return own_.Contains(tile); }
  // The reader's filter: its own tiles, and the other shards' to tell tiles on no region.
  transport::TileRegionSelection Selection() const;

  struct Outside {
    bool on_no_shard = false;  // else another shard's
    bool report_now = false;   // an orphan the log should name now (once a minute per robot)
  };
  // A fleet-frame tile outside this shard's tiles arrived.
  Outside NoteOutside(const RobotId& robot, const TileId& tile,
                      std::chrono::steady_clock::time_point now);

  uint64_t orphan_tiles() const { return orphan_tiles_; }
  uint64_t other_shards_tiles() const { return other_shards_tiles_; }

  static constexpr std::chrono::seconds kReportPeriod{60};
  static constexpr size_t kMaxRobotsTracked = 4096;  // beyond: reported as they come, no memory

 private:
  ShardAssignment shard_;
  double tile_size_;
  TileBox own_;
  std::vector<TileBox> others_;
  std::map<RobotId, std::chrono::steady_clock::time_point> last_report_;
  uint64_t orphan_tiles_ = 0;
  uint64_t other_shards_tiles_ = 0;
};

}  // namespace fleetmap::server
