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
// A sample the filter cannot read (a disposal carrying no payload, a short one) passes: the reader
// decides, as without a filter.

#include <cstdint>
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

  // Whether a sample of this tile passes.
  bool Passes(const TileId& tile) const;
  // As filter parameters; from them (an error names a parameter it cannot read).
  std::vector<std::string> ToParameters() const;
  static StatusOr<TileRegionSelection> FromParameters(const std::vector<std::string>& parameters);
};

}  // namespace fleetmap::transport
