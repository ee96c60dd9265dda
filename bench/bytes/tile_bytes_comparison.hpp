#pragma once

// A vector map's bytes on the fleet's wire against the grid's, tile by tile (issue 17): the
// vector tiles' samples over each of the grid's per-tile baselines, for one map or summed over
// several, and the headline a report leads with, the ratio to the smallest baseline. Below 1 the
// vector tiles are smaller. Any thread.

#include <string>
#include <vector>

#include "bench/bytes/grid_tile_bytes.hpp"
#include "bench/bytes/vector_tile_bytes.hpp"

namespace fleetmap::bench {

// vector bytes / a baseline's bytes, with the baseline's name ("zstd -19").
struct NamedRatio {
  std::string baseline;
  double ratio = 0.0;  // 0 when the baseline has no bytes
};

struct TileBytesComparison {
  TiledGridBytes grid;
  VectorTileBytes vector;

  TileBytesComparison& operator+=(const TileBytesComparison& other);
  // One per TileBaselines entry, in its order.
  std::vector<NamedRatio> Ratios() const;
  // Against SmallestTileBaseline.
  NamedRatio RatioToSmallest() const;
  // Against one baseline, e.g. &GridTileBytes::zstd19 (the targets name theirs).
  double RatioTo(size_t GridTileBytes::*baseline) const;
};

// The names of TileBaselines in report order, for column headers; the dictionary baseline's last
// when a report has it.
std::vector<std::string> TileBaselineNames(bool with_dictionary = false);

// Over several maps (or terrains): the summed vector bytes over the smallest summed baseline,
// and the map whose ratio to its own smallest baseline is the largest.
struct TileBytesHeadline {
  NamedRatio summed;
  NamedRatio worst;
  std::string worst_map;
};

struct NamedComparison {
  std::string name;
  TileBytesComparison bytes;
};

// Needs at least one map (a broken invariant otherwise).
TileBytesHeadline HeadlineOf(const std::vector<NamedComparison>& maps);

}  // namespace fleetmap::bench
