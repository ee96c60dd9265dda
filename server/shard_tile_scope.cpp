#include "server/shard_tile_scope.hpp"

namespace fleetmap::server {

ShardTileScope::ShardTileScope(ShardAssignment shard, double tile_size)
    : shard_(std::move(shard)), tile_size_(tile_size), own_(shard_.region().Tiles(tile_size)) {
  for (const ShardRegion& region : shard_.plan.regions()) {
    if (region.name != shard_.name) others_.push_back(region.Tiles(tile_size));
  }
}

transport::TileRegionSelection ShardTileScope::Selection() const {
  return transport::TileRegionSelection{own_, others_};
}

ShardTileScope::Outside ShardTileScope::NoteOutside(const RobotId& robot, const TileId& tile,
                                                    std::chrono::steady_clock::time_point now) {
  const bool on_no_shard = shard_.plan.OwnerOf(tile, tile_size_) == nullptr;
  if (!on_no_shard) {
    ++other_shards_tiles_;
    return Outside{false, false};
  }
  ++orphan_tiles_;
  const auto last = last_report_.find(robot);
  if (last != last_report_.end() && now - last->second < kReportPeriod) return Outside{true, false};
  if (last != last_report_.end()) {
    last->second = now;
  } else if (last_report_.size() < kMaxRobotsTracked) {
    last_report_.emplace(robot, now);
  }
  return Outside{true, true};
}

}  // namespace fleetmap::server
