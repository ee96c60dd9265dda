#pragma once

// What a shard's server reads of rt/fleetmap/robot_tiles (docs/shards.md): a DDS content filter of
// class FLEETMAP_TILE_REGION that every fleetmap participant registers, so an agent's writer
// evaluates it and sends a shard only what the shard fuses; a writer of another vendor sends
// everything, and the shard's own participant filters on arrival.
//
// The expression is kTileRegionFilterExpression; its parameters:
//   %0 %1 %2 %3      the shard's tiles: tile_x from %0 to %1, tile_y from %2 to %3 (inclusive)
//   "box:A,B,C,D"    (any number) another shard's tiles, the same four numbers: a tile on no
//                    shard's tiles passes too, so that every shard can say it is fused nowhere
//   "robots:a,b,..." (any number) robots whose tiles pass wherever they are: robots that send
//                    tiles in their own map frame, whose tile keys say nothing of the fleet frame
//   "all"            every tile passes
// A sample the filter cannot read (a disposal carrying no payload, a short one) passes: the reader
// decides, as without a filter.

#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"

namespace fleetmap::transport {

inline constexpr const char* kTileRegionFilterClass = "FLEETMAP_TILE_REGION";
inline constexpr const char* kTileRegionFilterExpression =
    "tile_x BETWEEN %0 AND %1 AND tile_y BETWEEN %2 AND %3";

// What a shard's reader lets through; the parameters above, as a value.
struct TileRegionSelection {
  TileBox own;
  std::vector<TileBox> others;
  std::set<std::string> whole_robots;
  bool everything = false;

  // Whether the tile (robot, tile) of a sample passes.
  bool Passes(std::string_view robot, const TileId& tile) const;
  // As filter parameters (each under the 255 characters DDS carries per parameter, and at most
  // kMaxParameters of them: past that, "all").
  std::vector<std::string> ToParameters() const;
  static StatusOr<TileRegionSelection> FromParameters(const std::vector<std::string>& parameters);

  static constexpr size_t kMaxParameters = 100;  // Fast DDS 2.9's default allocation
};

}  // namespace fleetmap::transport
