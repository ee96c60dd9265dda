#pragma once

// Where a server's published ids start (docs/shards.md). The shards of one fleet write the same
// keyed topics (object templates, objects, sub-maps, the route graph), and a reader takes each
// instance from one writer only (exclusive ownership), so each shard numbers its own: its place in
// the shard plan, counted from 1, times 2^24, plus the id it counts from 0; its route graph is
// named after it. An unsharded server starts at 0 and names its graph "fleet".

#include <cstdint>
#include <optional>
#include <string>

#include "common/core/shard_regions.hpp"

namespace fleetmap::server {

struct PublishedIds {
  uint32_t base = 0;
  std::string graph_id = "fleet";

  uint32_t operator()(uint32_t local_id) const { return base + local_id; }

  static PublishedIds For(const std::optional<ShardAssignment>& shard) {
    if (!shard) return {};
    const auto& regions = shard->plan.regions();
    uint32_t place = 1;
    while (place <= regions.size() && regions[place - 1].name != shard->name) ++place;
    return PublishedIds{place << kShardBits, shard->name};
  }

  static constexpr int kShardBits = 24;  // 16 M ids per shard, 255 shards
};

}  // namespace fleetmap::server
