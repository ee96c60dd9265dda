#pragma once

// Memory figures of a map (ALGORITHMS.md 1.1 "Memory"): raw bytes and the bytes after the
// compressors a user would reach for.

#include <cstddef>
#include <cstdint>
#include <span>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::metrics {

struct CompressedSizes {
  size_t raw = 0;
  size_t gzip = 0;  // gzip stream (header included), zlib level 9
  size_t zstd = 0;  // zstd level 19
};

// Sizes of any byte buffer (a grid's cells, an encoded vector map). Errors: a compressor failed.
StatusOr<CompressedSizes> MeasureBytes(std::span<const uint8_t> bytes);

struct GridSizes {
  CompressedSizes cells;  // one byte per cell (nav_msgs values)
  size_t png = 0;         // trinary PNG as map_server would save it (0 / 205 / 254)
};

StatusOr<GridSizes> MeasureGridSizes(const grid::OccupancyGrid& grid);

}  // namespace fleetmap::metrics
