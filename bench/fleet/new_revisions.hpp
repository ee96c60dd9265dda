#pragma once

#include <cstdint>
#include <map>

#include "common/core/ids.hpp"

namespace fleetmap::bench {

// Which fused tiles a reader receives are new fusion. A server that starts serving writes its
// served state again, old stamps and all (docs/standby.md), and a late reader gets the history:
// a latency measured on such a copy is the age of the tile, not the time fusion took. A benchmark
// measures latency only on the first sample of each revision.
class NewRevisions {
 public:
  // True when `revision` is newer than every revision of `tile` seen so far (and then remembers
  // it).
  bool Take(const TileId& tile, uint32_t revision) {
    uint32_t& newest = newest_[tile];
    if (revision <= newest) return false;
    newest = revision;
    return true;
  }

 private:
  std::map<TileId, uint32_t> newest_;
};

}  // namespace fleetmap::bench
