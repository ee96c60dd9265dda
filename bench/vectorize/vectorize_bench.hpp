#pragma once

// The measurements behind `fleetmap bench vectorize` for one map: ours (kDefault, obstacles only
// and with free space), the paper's method and the OpenCV baseline on the whole map in one
// thread (median of N runs), their vertex counts and whether both constraints hold, the bytes of
// the tiled .vmap against the 3-state grid, the round trip rasterize(vectorize(G)) against G, and
// the time to re-vectorize one changed tile, and where the vertices go (vertex_breakdown.hpp).
// Bytes are compared two ways: per fleet tile, each tile alone, as the fleet's wire sends them
// (the vector tiles' samples against the grid tiles' baselines, bench/bytes), and the whole map
// in one piece, as files.
// Not a test: it asserts nothing.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bench/bytes/tile_bytes_comparison.hpp"
#include "bench/bytes/tile_compression.hpp"
#include "bench/vectorize/vertex_breakdown.hpp"
#include "common/core/ids.hpp"
#include "common/core/status.hpp"

namespace fleetmap::bench {

struct VectorizeBenchOptions {
  int runs = 5;             // timings are medians of this many runs
  double tile_size = 10.0;  // metres, for the .vmap and the re-vectorized tile
  int64_t max_cells = 400'000'000;
  bool line_refit = true;  // VectorizerOptions::refit_lines of kDefault (off only to measure it)
  // The dictionary of the "zstd -19 + dictionary" grid baseline (not owned); none: not measured.
  const ZstdDictionary* grid_dictionary = nullptr;
};

// What the Validator found on one output.
struct ConstraintCheck {
  int64_t uncovered_points = 0;
  int64_t discontinuous_segments = 0;
  bool ok() const { return uncovered_points == 0 && discontinuous_segments == 0; }
};

struct MethodFigures {
  size_t vertices = 0;
  size_t segments = 0;
  double ms = 0.0;  // median
  ConstraintCheck check;
};

struct VectorizeBenchRow {
  std::string name;  // file stem
  int64_t cells = 0;
  double resolution = 0.0;
  double epsilon = 0.0;    // metres
  double tile_size = 0.0;  // metres, of the .vmap's tiles and the byte comparison's

  MethodFigures ours;           // kDefault, obstacles only
  MethodFigures ours_full;      // kDefault with free space; vertices = obstacles + free
  MethodFigures paper;          // obstacles only
  MethodFigures opencv;         // mask + findContours + approxPolyDP
  double opencv_mask_ms = 0.0;  // of opencv.ms: building the occupied mask from the grid
  // ours (obstacles) and OpenCV's vertices by the size of the occupied component they stand for.
  VertexBreakdown vertices_by_component;

  // The tiled .vmap (with free space) as `fleetmap vectorize` writes it.
  ConstraintCheck vmap_check;
  size_t vmap_tiles = 0;
  size_t vmap_dropped_free_rings = 0;
  size_t vmap_raw = 0;
  size_t vmap_zstd = 0;
  size_t vmap_obstacles_raw = 0;  // the same without free space
  size_t vmap_obstacles_zstd = 0;
  // The 3-state grid whole, in one piece: cells, zstd -19, and map_server's PNG file.
  size_t grid_raw = 0;
  size_t grid_zstd = 0;
  size_t grid_png = 0;

  // Per fleet tile (tile_size), each tile alone: the .vmap's tiles as the samples a robot agent
  // publishes against the same tiles of the 3-state grid on the grid's baselines.
  TileBytesComparison tile_bytes;

  // rasterize(decode(.vmap)) over G's geometry against G.
  std::optional<double> round_trip_ms;  // MS
  std::optional<double> round_trip_opdf;
  std::optional<double> round_trip_updf;

  TileId changed_tile;
  int changed_cells = 0;
  double revectorize_tile_ms = 0.0;  // median, the busiest tile
  struct TileUpdate {
    TileId tile;
    double ms = 0.0;  // median
  };
  std::vector<TileUpdate> tile_updates;  // every tile that has known cells
};

// Measures one map_server map. Errors name the file (load, vectorize or encode failures).
StatusOr<VectorizeBenchRow> MeasureVectorizeBench(const std::string& yaml_path,
                                                  const VectorizeBenchOptions& options);

}  // namespace fleetmap::bench
