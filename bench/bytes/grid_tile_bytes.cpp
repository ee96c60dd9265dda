#include "bench/bytes/grid_tile_bytes.hpp"

#include <algorithm>
#include <span>

#include "bench/bytes/tile_compression.hpp"
#include "common/core/check.hpp"
#include "common/grid/tiling.hpp"
#include "common/transport/map_update_payload.hpp"

namespace fleetmap::bench {
namespace {

// A ROS 2 SLAM node's map frame; its length sets the patch header's size (docs of the payload).
constexpr char kPatchFrameId[] = "map";

// Compressed zstd levels of the baselines: -3 is zstd's default, what a node would pick for
// speed; -19 the smallest a sender could afford per update.
constexpr int kZstdFast = 3;
constexpr int kZstdSmall = 19;

constexpr char kZstdDictionaryBaseline[] = "zstd -19 + dictionary";

transport::MapUpdate Patch(const grid::OccupancyGrid& grid, const grid::CellRect& cells) {
  transport::MapUpdate patch;
  patch.x = cells.x0;
  patch.y = cells.y0;
  patch.width = cells.width;
  patch.height = cells.height;
  patch.data.reserve(static_cast<size_t>(cells.cell_count()));
  for (int y = cells.y0; y < cells.y0 + cells.height; ++y) {
    const auto row = grid.data().begin() + static_cast<int64_t>(y) * grid.width() + cells.x0;
    patch.data.insert(patch.data.end(), row, row + cells.width);
  }
  return patch;
}

bool AllUnknown(const grid::OccupancyGrid& grid, const grid::CellRect& cells) {
  for (int y = cells.y0; y < cells.y0 + cells.height; ++y) {
    for (int x = cells.x0; x < cells.x0 + cells.width; ++x) {
      if (grid.at(x, y) != grid::kUnknownValue) return false;
    }
  }
  return true;
}

}  // namespace

GridTileBytes& GridTileBytes::operator+=(const GridTileBytes& other) {
  raw += other.raw;
  patch_cdr += other.patch_cdr;
  zstd3 += other.zstd3;
  zstd19 += other.zstd19;
  lz4 += other.lz4;
  zstd19_dict += other.zstd19_dict;
  return *this;
}

std::vector<NamedBytes> TileBaselines(const GridTileBytes& bytes) {
  std::vector<NamedBytes> baselines = {{"patch CDR", bytes.patch_cdr},
                                       {"zstd -3", bytes.zstd3},
                                       {"zstd -19", bytes.zstd19},
                                       {"LZ4", bytes.lz4}};
  if (bytes.zstd19_dict > 0) baselines.push_back({kZstdDictionaryBaseline, bytes.zstd19_dict});
  return baselines;
}

NamedBytes SmallestTileBaseline(const GridTileBytes& bytes) {
  const std::vector<NamedBytes> baselines = TileBaselines(bytes);
  return *std::min_element(
      baselines.begin(), baselines.end(),
      [](const NamedBytes& a, const NamedBytes& b) { return a.bytes < b.bytes; });
}

StatusOr<GridTileBytes> MeasureGridTileBytes(const grid::OccupancyGrid& grid,
                                             const grid::CellRect& cells,
                                             const ZstdDictionary* dictionary) {
  FLEETMAP_CHECK(!cells.empty() && grid.Contains(cells.x0, cells.y0) &&
                     grid.Contains(cells.x0 + cells.width - 1, cells.y0 + cells.height - 1),
                 "a grid tile's cells must lie inside the grid");
  const transport::MapUpdate patch = Patch(grid, cells);
  const std::span<const uint8_t> cell_bytes(reinterpret_cast<const uint8_t*>(patch.data.data()),
                                            patch.data.size());
  GridTileBytes bytes;
  bytes.raw = cell_bytes.size();
  bytes.patch_cdr = transport::EncodeMapUpdatePayload(patch, kPatchFrameId).size();
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> zstd3, CompressZstd(cell_bytes, kZstdFast));
  bytes.zstd3 = zstd3.size();
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> zstd19,
                            CompressZstd(cell_bytes, kZstdSmall));
  bytes.zstd19 = zstd19.size();
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> lz4, CompressLz4(cell_bytes));
  bytes.lz4 = lz4.size();
  if (dictionary != nullptr) {
    FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> frame,
                              dictionary->Compress(cell_bytes, kZstdSmall));
    bytes.zstd19_dict = frame.size();
  }
  return bytes;
}

StatusOr<TiledGridBytes> MeasureTiledGridBytes(const grid::OccupancyGrid& grid,
                                               const Transform2& fleet_from_map, double tile_size,
                                               const ZstdDictionary* dictionary) {
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects, grid::TileCellRects(grid, fleet_from_map, tile_size));
  TiledGridBytes tiled;
  for (const auto& [tile, cells] : rects) {
    if (cells.empty() || AllUnknown(grid, cells)) continue;
    FLEETMAP_ASSIGN_OR_RETURN(const GridTileBytes bytes,
                              MeasureGridTileBytes(grid, cells, dictionary));
    tiled.bytes += bytes;
    ++tiled.tiles;
  }
  return tiled;
}

StatusOr<std::vector<std::vector<uint8_t>>> GridTileSamples(const grid::OccupancyGrid& grid,
                                                            const Transform2& fleet_from_map,
                                                            double tile_size) {
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects, grid::TileCellRects(grid, fleet_from_map, tile_size));
  std::vector<std::vector<uint8_t>> samples;
  for (const auto& [tile, cells] : rects) {
    if (cells.empty() || AllUnknown(grid, cells)) continue;
    const transport::MapUpdate patch = Patch(grid, cells);
    const auto* first = reinterpret_cast<const uint8_t*>(patch.data.data());
    samples.emplace_back(first, first + patch.data.size());
  }
  return samples;
}

}  // namespace fleetmap::bench
