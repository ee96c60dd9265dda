#include "bench/vectorize/vectorize_bench.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <span>
#include <utility>
#include <vector>

#include "bench/report/report_format.hpp"
#include "bench/vectorize/opencv_contours.hpp"
#include "cli/inputs/command_inputs.hpp"
#include "common/grid/tiling.hpp"
#include "common/metrics/grid_sizes.hpp"
#include "common/metrics/map_quality.hpp"
#include "common/transport/vmap_file.hpp"
#include "common/vector_map/rasterizer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "common/vector_map/validator.hpp"
#include "common/vector_map/vectorizer.hpp"

namespace fleetmap::bench {
namespace {

using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The median time of `runs` calls of `run` (which stores its last result itself).
template <typename Run>
double MedianMs(int runs, Run&& run) {
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const Clock::time_point start = Clock::now();
    run();
    times.push_back(MillisecondsSince(start));
  }
  return Median(std::move(times));
}

// The grid as the three values a vector map can give back: 100, 0, -1.
grid::OccupancyGrid ThreeState(const grid::OccupancyGrid& source) {
  grid::OccupancyGrid grid = source;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      switch (source.StateAt(x, y)) {
        case grid::CellState::kOccupied:
          grid.at(x, y) = grid::kOccupiedValue;
          break;
        case grid::CellState::kFree:
          grid.at(x, y) = grid::kFreeValue;
          break;
        case grid::CellState::kUnknown:
          grid.at(x, y) = grid::kUnknownValue;
          break;
      }
    }
  }
  return grid;
}

StatusOr<ConstraintCheck> Check(const vector_map::VectorMap& map, const grid::OccupancyGrid& grid,
                                double epsilon) {
  vector_map::ValidatorOptions options;
  options.epsilon = epsilon;
  options.measure_segment_distance = false;
  FLEETMAP_ASSIGN_OR_RETURN(const vector_map::ValidationReport report,
                            vector_map::Validator(options).Validate(map, grid));
  return ConstraintCheck{report.uncovered_points, report.discontinuous_segments};
}

// Whole-map vectorization with one method, timed. `output` (optional) receives the map.
StatusOr<MethodFigures> MeasureOurs(const grid::OccupancyGrid& grid,
                                    vector_map::VectorizeMethod method, bool free_space,
                                    const VectorizeBenchOptions& bench,
                                    vector_map::VectorMap* output = nullptr) {
  const int runs = bench.runs;
  vector_map::VectorizerOptions options;
  options.method = method;
  options.extract_free_space = free_space;
  options.refit_lines = bench.line_refit;
  const vector_map::Vectorizer vectorizer(options);
  StatusOr<vector_map::VectorMap> map = vectorizer.Vectorize(grid);
  if (!map.ok()) return map.status();
  MethodFigures figures;
  figures.ms = MedianMs(runs, [&] { map = vectorizer.Vectorize(grid); });
  figures.vertices = map->ObstacleVertexCount() + map->FreeVertexCount();
  figures.segments = map->ObstacleSegmentCount();
  FLEETMAP_ASSIGN_OR_RETURN(figures.check, Check(*map, grid, map->epsilon));
  if (output != nullptr) *output = std::move(*map);
  return figures;
}

struct EncodedSizes {
  size_t raw = 0;
  size_t zstd = 0;
};

StatusOr<EncodedSizes> Sizes(const std::string& bytes) {
  FLEETMAP_ASSIGN_OR_RETURN(const metrics::CompressedSizes sizes,
                            metrics::MeasureBytes(std::span(
                                reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size())));
  return EncodedSizes{sizes.raw, sizes.zstd};
}

// The full tile (largest rectangle) with the most occupied cells: where a change costs most.
std::pair<TileId, grid::CellRect> BusiestTile(const grid::OccupancyGrid& grid,
                                              const std::map<TileId, grid::CellRect>& rects) {
  std::pair<TileId, grid::CellRect> best = *rects.begin();
  int64_t best_score = -1;
  for (const auto& [id, rect] : rects) {
    int64_t occupied = 0;
    for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
      for (int x = rect.x0; x < rect.x0 + rect.width; ++x) {
        occupied += grid.StateAt(x, y) == grid::CellState::kOccupied ? 1 : 0;
      }
    }
    const int64_t score = rect.cell_count() * (int64_t{1} << 32) + occupied;
    if (score > best_score) {
      best_score = score;
      best = {id, rect};
    }
  }
  return best;
}

// Flips a few cells (occupied <-> free) in a plus around the tile's centre; calling it twice
// restores the grid. Returns how many cells it flipped.
int FlipCells(const grid::CellRect& rect, grid::OccupancyGrid* grid) {
  const int cx = rect.x0 + rect.width / 2;
  const int cy = rect.y0 + rect.height / 2;
  const int offsets[][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  int flipped = 0;
  for (const auto& offset : offsets) {
    const int x = cx + offset[0];
    const int y = cy + offset[1];
    if (!rect.Contains(x, y)) continue;
    int8_t& value = grid->at(x, y);
    value = value == grid::kOccupiedValue ? grid::kFreeValue : grid::kOccupiedValue;
    ++flipped;
  }
  return flipped;
}

vector_map::TiledVectorizeOptions TiledOptions(const VectorizeBenchOptions& options,
                                               bool free_space) {
  vector_map::TiledVectorizeOptions tiled;
  tiled.tile_size = options.tile_size;
  tiled.vectorizer.extract_free_space = free_space;
  tiled.vectorizer.refit_lines = options.line_refit;
  return tiled;
}

// The full .vmap as `fleetmap vectorize` writes it, and what a reader of the file gets: decode,
// validate, rasterize over G's geometry, compare with G. Returns the tiles for the update test.
StatusOr<vector_map::TiledVectorMap> MeasureVmap(const grid::OccupancyGrid& grid,
                                                 const VectorizeBenchOptions& options,
                                                 VectorizeBenchRow* row) {
  FLEETMAP_ASSIGN_OR_RETURN(
      vector_map::TiledVectorMap tiled,
      vector_map::VectorizeTiled(grid, Transform2::Identity(), TiledOptions(options, true)));
  row->vmap_tiles = tiled.tiles.size();
  FLEETMAP_ASSIGN_OR_RETURN(const std::string bytes,
                            cli::EncodeVmapBytes(&tiled, &row->vmap_dropped_free_rings));
  FLEETMAP_ASSIGN_OR_RETURN(const EncodedSizes full, Sizes(bytes));
  row->vmap_raw = full.raw;
  row->vmap_zstd = full.zstd;
  FLEETMAP_ASSIGN_OR_RETURN(row->tile_bytes.vector, MeasureVectorTileBytes(tiled));
  FLEETMAP_ASSIGN_OR_RETURN(row->tile_bytes.grid,
                            MeasureTiledGridBytes(grid, Transform2::Identity(), options.tile_size,
                                                  options.grid_dictionary));

  FLEETMAP_ASSIGN_OR_RETURN(const vector_map::TiledVectorMap decoded,
                            transport::DecodeVmap(bytes, row->name + ".vmap"));
  const vector_map::VectorMap merged = decoded.Merged();
  FLEETMAP_ASSIGN_OR_RETURN(row->vmap_check,
                            Check(merged, grid, cli::StoredEpsilonBound(decoded.epsilon)));
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid raster,
                            vector_map::Rasterizer().Rasterize(merged, grid));
  FLEETMAP_ASSIGN_OR_RETURN(const metrics::QualityScores scores,
                            metrics::CompareMaps(raster, grid));
  row->round_trip_ms = scores.map_score;
  row->round_trip_opdf = scores.occupied_picture_distance;
  row->round_trip_updf = scores.unoccupied_picture_distance;
  return tiled;
}

// The .vmap without free space.
Status MeasureObstacleVmap(const grid::OccupancyGrid& grid, const VectorizeBenchOptions& options,
                           VectorizeBenchRow* row) {
  FLEETMAP_ASSIGN_OR_RETURN(
      const vector_map::TiledVectorMap obstacles,
      vector_map::VectorizeTiled(grid, Transform2::Identity(), TiledOptions(options, false)));
  FLEETMAP_ASSIGN_OR_RETURN(const std::string bytes, transport::EncodeVmap(obstacles));
  FLEETMAP_ASSIGN_OR_RETURN(const EncodedSizes sizes, Sizes(bytes));
  row->vmap_obstacles_raw = sizes.raw;
  row->vmap_obstacles_zstd = sizes.zstd;
  return Status::Ok();
}

// One changed tile: flip a few cells, re-vectorize that tile only. Each run flips the same cells
// back or forth, so every run sees a real change.
Status MeasureTileUpdate(const grid::OccupancyGrid& grid, const VectorizeBenchOptions& options,
                         vector_map::TiledVectorMap* tiled, VectorizeBenchRow* row) {
  FLEETMAP_ASSIGN_OR_RETURN(const auto rects,
                            grid::TileCellRects(grid, Transform2::Identity(), options.tile_size));
  const auto [tile, rect] = BusiestTile(grid, rects);
  row->changed_tile = tile;
  const vector_map::TiledVectorizeOptions tiled_options = TiledOptions(options, true);
  grid::OccupancyGrid changed = grid;
  std::vector<double> times;
  for (int i = 0; i < options.runs; ++i) {
    row->changed_cells = FlipCells(rect, &changed);
    const Clock::time_point start = Clock::now();
    const Status status =
        vector_map::RevectorizeTile(changed, Transform2::Identity(), tile, tiled_options, tiled);
    times.push_back(MillisecondsSince(start));
    FLEETMAP_RETURN_IF_ERROR(status);
  }
  row->revectorize_tile_ms = Median(std::move(times));

  // Every other tile as well: the busiest one is the worst case, not the typical update.
  // RevectorizeTile redoes its whole tile whether or not a cell changed, so no flip is needed.
  for (const auto& [id, cells] : rects) {
    if (!tiled->tiles.contains(id)) continue;  // all unknown: nothing to redo
    Status status = Status::Ok();
    const double ms = MedianMs(options.runs, [&] {
      status =
          vector_map::RevectorizeTile(changed, Transform2::Identity(), id, tiled_options, tiled);
    });
    row->tile_updates.push_back({id, ms});
    FLEETMAP_RETURN_IF_ERROR(status);
  }
  return Status::Ok();
}

// Fills row->opencv; `ours` (obstacles) is broken down beside OpenCV's output.
Status MeasureOpenCv(const grid::OccupancyGrid& grid, int runs, const vector_map::VectorMap& ours,
                     VectorizeBenchRow* row) {
  const double epsilon_cells = row->epsilon / grid.resolution();
  Contours contours;
  cv::Mat mask;
  std::vector<double> totals;
  std::vector<double> masks;
  for (int i = 0; i < runs; ++i) {
    const Clock::time_point start = Clock::now();
    mask = OccupiedMask(grid);
    masks.push_back(MillisecondsSince(start));
    contours = OpenCvVectorize(mask, epsilon_cells);
    totals.push_back(MillisecondsSince(start));
  }
  row->opencv.ms = Median(std::move(totals));
  row->opencv_mask_ms = Median(std::move(masks));
  const vector_map::VectorMap map = ContoursToVectorMap(contours, grid, row->epsilon);
  row->opencv.vertices = map.ObstacleVertexCount();
  row->opencv.segments = map.ObstacleSegmentCount();
  FLEETMAP_ASSIGN_OR_RETURN(row->opencv.check, Check(map, grid, row->epsilon));
  row->vertices_by_component = BreakDownVertices(grid, mask, ours, contours, row->epsilon);
  return Status::Ok();
}

StatusOr<VectorizeBenchRow> Measure(const std::string& yaml_path,
                                    const VectorizeBenchOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(const grid::LoadedMap loaded,
                            cli::LoadGridInput(yaml_path, options.max_cells));
  FLEETMAP_RETURN_IF_ERROR(cli::CheckAxisAligned(yaml_path, loaded.grid));
  const grid::OccupancyGrid grid = ThreeState(loaded.grid);
  VectorizeBenchRow row;
  row.name = std::filesystem::path(yaml_path).stem().string();
  row.cells = grid.cell_count();
  row.resolution = grid.resolution();
  row.epsilon = vector_map::DefaultEpsilon(grid.resolution());
  row.tile_size = options.tile_size;

  using vector_map::VectorizeMethod;
  vector_map::VectorMap ours;
  FLEETMAP_ASSIGN_OR_RETURN(row.ours,
                            MeasureOurs(grid, VectorizeMethod::kDefault, false, options, &ours));
  FLEETMAP_ASSIGN_OR_RETURN(row.ours_full,
                            MeasureOurs(grid, VectorizeMethod::kDefault, true, options));
  FLEETMAP_ASSIGN_OR_RETURN(row.paper, MeasureOurs(grid, VectorizeMethod::kPaper, false, options));
  FLEETMAP_RETURN_IF_ERROR(MeasureOpenCv(grid, options.runs, ours, &row));

  FLEETMAP_ASSIGN_OR_RETURN(const metrics::GridSizes grid_sizes, metrics::MeasureGridSizes(grid));
  row.grid_raw = grid_sizes.cells.raw;
  row.grid_zstd = grid_sizes.cells.zstd;
  row.grid_png = grid_sizes.png;
  FLEETMAP_ASSIGN_OR_RETURN(vector_map::TiledVectorMap tiled, MeasureVmap(grid, options, &row));
  FLEETMAP_RETURN_IF_ERROR(MeasureObstacleVmap(grid, options, &row));
  FLEETMAP_RETURN_IF_ERROR(MeasureTileUpdate(grid, options, &tiled, &row));
  return row;
}

}  // namespace

StatusOr<VectorizeBenchRow> MeasureVectorizeBench(const std::string& yaml_path,
                                                  const VectorizeBenchOptions& options) {
  StatusOr<VectorizeBenchRow> row = Measure(yaml_path, options);
  if (!row.ok() && row.status().message().find(yaml_path) == std::string::npos) {
    return row.status().WithContext(yaml_path);
  }
  return row;
}

}  // namespace fleetmap::bench
