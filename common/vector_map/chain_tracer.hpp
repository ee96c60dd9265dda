#pragma once

// Skeleton pixels -> chains of pixels (docs/vector-maps.md, kDefault step 3).
//
// Pixels are linked with m-adjacency (a diagonal link only if neither shared 4-neighbour is
// skeleton), so L-shaped corners read as paths, not junctions. Chains run between pixels of degree
// != 2; pure rings of degree-2 pixels are chains whose last pixel repeats the first. Then chains
// are **merged through junctions**: at a pixel of degree >= 3 the incident chain ends are paired,
// straightest continuation first (the two directions closest to opposite), and each pair becomes
// one chain passing through the junction. A junction pixel is then an interior vertex of the
// merged chains (often simplified away) and an end of at most one chain, instead of being stored
// once per incident chain.

#include <vector>

#include "common/vector_map/cell_raster.hpp"

namespace fleetmap::vector_map {

struct PixelChain {
  std::vector<int> pixels;  // raster indices; a ring repeats its first pixel at the end
  bool ring() const { return pixels.size() > 2 && pixels.front() == pixels.back(); }
};

// Degree of a skeleton pixel under m-adjacency.
int SkeletonDegree(const CellRaster& raster, int index);

// `skeleton`: the pixels with CellRaster::kSkeleton set. Uses and clears CellRaster::kVisited.
// Single pixels (degree 0) are returned as one-pixel chains.
std::vector<PixelChain> TraceChains(CellRaster& raster, const std::vector<int>& skeleton);

}  // namespace fleetmap::vector_map
