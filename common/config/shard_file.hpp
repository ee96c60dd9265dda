#pragma once

// The shards of a fleet, from a YAML file every shard server (and the aggregator) reads:
//
//   shards:
//     west: [0.0, 0.0, 60.0, 40.0]     # X0 Y0 X1 Y1: the region, metres in the fleet frame
//     east: [60.0, 0.0, 120.0, 40.0]
//   robots:                            # optional: the shard that places a robot at an unknown
//     delta: east                      # pose (its home); the others follow. Default: the first.
//
// Listed in the order of the file; regions must not overlap (docs/shards.md).

#include <string>

#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"

namespace fleetmap::config {

// Errors name the file and the entry: missing file, YAML syntax, no `shards` map, a value that is
// not four finite numbers, and every error of ShardPlan::Create.
StatusOr<ShardPlan> LoadShardPlan(const std::string& path);

}  // namespace fleetmap::config
