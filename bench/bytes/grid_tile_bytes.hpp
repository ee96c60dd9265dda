#pragma once

// The honest baselines for a vector tile's bytes (issue 17): what the same fleet tile of the
// occupancy grid costs when the grid travels tile by tile, each tile alone. A tile is the cells
// of one fleet-frame tile (common/grid/tiling.hpp), int8 as on the ROS wire (100 / 0 / -1 and
// the values between). Baselines:
//  - patch CDR: the map_msgs/OccupancyGridUpdate sample of the tile as a ROS 2 SLAM node sends it
//    (transport::EncodeMapUpdatePayload, the real IDL encoder: 40 bytes of header, then the cells);
//  - zstd -3, zstd -19, LZ4 (block): the cells compressed alone. Only the cells are counted, not
//    the patch header a compressed patch would still need, so these favour the grid;
//  - zstd -19 + dictionary, when a dictionary is given: the cells compressed alone against a zstd
//    dictionary trained on the grid tiles of other maps (tile_compression.hpp), the strongest grid
//    wire a careful engineer would build; the dictionary itself is not counted.
// Not a test: it asserts nothing. Any thread.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bench/bytes/tile_compression.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

struct GridTileBytes {
  size_t raw = 0;          // the cells, one byte each
  size_t patch_cdr = 0;    // the OccupancyGridUpdate sample, encapsulation header included
  size_t zstd3 = 0;        // the cells, zstd -3
  size_t zstd19 = 0;       // the cells, zstd -19
  size_t lz4 = 0;          // the cells, LZ4 block
  size_t zstd19_dict = 0;  // the cells, zstd -19 against a trained dictionary; 0: not measured

  GridTileBytes& operator+=(const GridTileBytes& other);
};

// A baseline's name ("zstd -19"), as report columns print it, and its bytes.
struct NamedBytes {
  std::string name;
  size_t bytes = 0;
};

// The baselines a vector tile is compared with, in report order: patch CDR, zstd -3, zstd -19,
// LZ4, and zstd -19 + dictionary when it was measured. `raw` is not one: no wire sends bare cells
// without a header.
std::vector<NamedBytes> TileBaselines(const GridTileBytes& bytes);
// The smallest of TileBaselines (the first in report order on a tie).
NamedBytes SmallestTileBaseline(const GridTileBytes& bytes);

// The baselines of the cells `cells` of `grid` (inside it, not empty; a broken invariant
// otherwise), sent as a patch at (cells.x0, cells.y0) of the map; the dictionary baseline too
// when `dictionary` is given. Errors: a compressor failed.
StatusOr<GridTileBytes> MeasureGridTileBytes(const grid::OccupancyGrid& grid,
                                             const grid::CellRect& cells,
                                             const ZstdDictionary* dictionary = nullptr);

// The baselines of every fleet tile of `grid` summed: the tiles SplitIntoTiles cuts (found by
// TileCellRects, which makes the same assignment), without the all-unknown ones (the vector wire
// sends nothing for those either).
struct TiledGridBytes {
  size_t tiles = 0;
  GridTileBytes bytes;
};

// Errors: tiling (grid not axis-aligned in the fleet frame, bad tile size) or a compressor.
StatusOr<TiledGridBytes> MeasureTiledGridBytes(const grid::OccupancyGrid& grid,
                                               const Transform2& fleet_from_map, double tile_size,
                                               const ZstdDictionary* dictionary = nullptr);

// The cells of every fleet tile of `grid` that MeasureTiledGridBytes counts, one byte string per
// tile: what a grid dictionary is trained on. Errors: tiling.
StatusOr<std::vector<std::vector<uint8_t>>> GridTileSamples(const grid::OccupancyGrid& grid,
                                                            const Transform2& fleet_from_map,
                                                            double tile_size);

}  // namespace fleetmap::bench
