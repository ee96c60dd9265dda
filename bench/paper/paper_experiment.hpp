#pragma once

// The experiment of the Vector Maps paper (seed 002, section 5; ALGORITHMS.md 1.2) on simulated
// terrains: for one terrain (kind, size, seed) generate the ground truth, let a robot explore and
// map it, vectorize the robot map and the ground truth, and measure sizes (P, PZ, V, VZ and their
// zstd variants; the grid's per-tile baselines against the vector tiles) and the five quality
// metrics of (a) the robot grid, (b) the vector map of the robot grid and (c) the vector map of
// the ground truth, all against the ground truth.
// `fleetmap bench paper` runs it over the nine terrains and writes the report.

#include <cstdint>
#include <functional>
#include <string>

#include "bench/bytes/tile_bytes_comparison.hpp"
#include "common/core/status.hpp"
#include "common/metrics/grid_sizes.hpp"
#include "common/metrics/map_quality.hpp"
#include "common/sim/exploration_simulator.hpp"
#include "common/sim/terrain.hpp"

namespace fleetmap::bench {

struct PaperTerrainOptions {
  sim::TerrainKind kind = sim::TerrainKind::kOffice;
  double size = 10.0;  // metres
  uint32_t seed = 0;
  double resolution = 0.05;
  sim::ExplorationOptions exploration;  // its seed is derived from `seed`
  bool line_refit = true;               // VectorizerOptions::refit_lines
  // Where the maps' PNGs (and the robot map as YAML + PGM) go; empty writes nothing.
  std::string image_dir;
};

struct PaperTerrainResult {
  sim::TerrainKind kind = sim::TerrainKind::kOffice;
  double size = 0.0;
  uint32_t seed = 0;
  int width = 0;  // cells
  int height = 0;
  int scans = 0;
  double distance = 0.0;          // metres driven
  bool explored = false;          // no frontier left (not stopped by a budget)
  double observed_free = 0.0;     // fraction of the truth's free cells the robot map knows
  metrics::CompressedSizes grid;  // P (raw), PZ (gzip -9), zstd -19
  size_t grid_png = 0;
  metrics::CompressedSizes vmap;  // V (.vmap bytes), VZ (gzip -9), zstd -19
  // The same tiles without their free-space polygons: obstacles only, as the paper's vector map.
  metrics::CompressedSizes vmap_obstacles;
  // Obstacles only with the whole terrain as one tile: one vector map of the terrain in one file,
  // as the paper's V is (10 m tiles, above, are what the fleet sends: per-tile headers and seams).
  size_t vmap_obstacles_one_tile = 0;
  // The honest baselines (issue 17): the robot grid cut into the fleet's 10 m tiles, each tile
  // alone (patch CDR, zstd -3, zstd -19, LZ4), against V's tiles as the samples an agent sends.
  TileBytesComparison tile_bytes;
  size_t vertices = 0;
  size_t segments = 0;
  size_t truth_vmap = 0;                // .vmap bytes of the ground truth's vector map
  metrics::QualityScores robot;         // (a)
  metrics::QualityScores robot_vector;  // (b)
  metrics::QualityScores truth_vector;  // (c)
  // Where MS changes by vectorizing: cells the robot grid has right (equal to the truth) and its
  // vector map gets wrong, by (robot grid state, rasterized state), indexed by grid::CellState;
  // and cells the robot grid has wrong and its vector map right. MS(a) - MS(b) =
  // 100 * (sum(lost) - gained) / cells.
  int64_t lost[3][3] = {};
  int64_t gained = 0;
  double seconds_explore = 0.0;
  double seconds_vectorize = 0.0;
  double seconds_total = 0.0;
};

// `stage` is called with a short description of what runs next ("exploring 1200 scans"...).
StatusOr<PaperTerrainResult> RunPaperTerrain(
    const PaperTerrainOptions& options,
    const std::function<void(const std::string& stage)>& stage = {});

}  // namespace fleetmap::bench
