#pragma once

#include <cstdint>

#include "common/fusion/fusion_options.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::fusion {

// What one robot tile costs the server once decoded: its vertices and free rings, the cells its
// geometry paints when fusion rasterizes it (free polygons' areas and obstacles' bands, in cells of
// the fused grid, summed: overlapping polygons cost each time), and the memory the server holds
// for it. Budgets count these, never the compressed bytes a tile arrives as.
struct TileCost {
  uint64_t vertices = 0;
  uint64_t rings = 0;
  uint64_t cells = 0;
  uint64_t bytes = 0;

  TileCost& operator+=(const TileCost& other);
  TileCost& operator-=(const TileCost& other);  // each field saturates at 0
  friend bool operator==(const TileCost&, const TileCost&) = default;
};

// Bytes the server holds per tile a robot contributes, per cell of the fused tile grid: the
// rasterized cells (1 byte) and their evidence dates (4), the fused tile's own state where the
// robot is alone there, the session archive and the store's queue. Calibrated on the server's
// RSS: 4 peers' 2,209 fused tiles of walls held about 1 GB over a 34 MB server, about 470 KB a
// 10 m tile (docs/results.md).
inline constexpr uint64_t kBytesPerContributedCell = 12;
// Bytes per vertex held: the queued tile, the session archive's copy and the stored payload.
inline constexpr uint64_t kBytesPerVertex = 48;
inline constexpr uint64_t kBytesPerRing = 32;
inline constexpr uint64_t kBytesPerTile = 1024;

// The cost of `map` as a tile of the fleet `fusion` describes. O(vertices), no allocation.
TileCost CostOf(const vector_map::VectorMap& map, const fusion::FusionOptions& fusion);
// What a tile whose geometry is not at hand (restored from the store) is counted as.
TileCost CostOfUnknownTile(const fusion::FusionOptions& fusion);
// Cells of one fused tile grid (FusionOptions::CellsPerTile() is cells per side).
uint64_t CellsPerTile(const fusion::FusionOptions& fusion);

}  // namespace fleetmap::fusion
