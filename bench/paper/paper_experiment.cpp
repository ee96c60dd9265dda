#include "bench/paper/paper_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <span>
#include <string>
#include <vector>

#include "bench/bytes/grid_tile_bytes.hpp"
#include "bench/bytes/vector_tile_bytes.hpp"
#include "common/core/file_io.hpp"
#include "common/grid/map_io.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"
#include "common/transport/vmap_file.hpp"
#include "common/vector_map/png.hpp"
#include "common/vector_map/rasterizer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::bench {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::span<const uint8_t> Bytes(const std::string& s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

// The vector map of `grid` as a fleet tile set (map frame = fleet frame) and its .vmap bytes.
struct Vectorized {
  vector_map::TiledVectorMap tiled;
  std::string vmap;
};

// `tile_size` <= 0: the fleet's default tiles.
StatusOr<Vectorized> Vectorize(const grid::OccupancyGrid& grid, bool line_refit,
                               bool free_space = true, double tile_size = 0.0) {
  Vectorized out;
  vector_map::TiledVectorizeOptions options;
  options.vectorizer.refit_lines = line_refit;
  options.vectorizer.extract_free_space = free_space;
  if (tile_size > 0.0) options.tile_size = tile_size;
  FLEETMAP_ASSIGN_OR_RETURN(out.tiled,
                            vector_map::VectorizeTiled(grid, Transform2::Identity(), options));
  FLEETMAP_ASSIGN_OR_RETURN(out.vmap, transport::EncodeVmap(out.tiled));
  return out;
}

}  // namespace

StatusOr<PaperTerrainResult> RunPaperTerrain(
    const PaperTerrainOptions& options,
    const std::function<void(const std::string& stage)>& stage) {
  const Clock::time_point start = Clock::now();
  auto report = [&](const std::string& what) {
    if (stage) stage(what);
  };
  PaperTerrainResult result;
  result.kind = options.kind;
  result.size = options.size;
  result.seed = options.seed;

  report("terrain");
  FLEETMAP_ASSIGN_OR_RETURN(
      const sim::TerrainGenerator generator,
      sim::TerrainGenerator::Create(
          {.kind = options.kind, .size = options.size, .seed = options.seed}));
  const sim::Terrain terrain = generator.Generate();
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid truth,
                            sim::RasterizeTerrain(terrain, options.resolution));
  result.width = truth.width();
  result.height = truth.height();

  report("exploring");
  sim::ExplorationOptions exploration = options.exploration;
  exploration.seed = options.seed * 1000003u + static_cast<uint32_t>(options.size) * 7u +
                     static_cast<uint32_t>(options.kind);
  FLEETMAP_ASSIGN_OR_RETURN(const sim::ExplorationSimulator simulator,
                            sim::ExplorationSimulator::Create(exploration));
  const Clock::time_point explore_start = Clock::now();
  FLEETMAP_ASSIGN_OR_RETURN(
      const sim::ExplorationResult run,
      simulator.Run(truth, terrain.start, [&](const sim::ExplorationProgress& progress) {
        report("exploring, " + std::to_string(progress.scans) + " scans, " +
               std::to_string(static_cast<int>(progress.distance)) + " m");
      }));
  result.seconds_explore = SecondsSince(explore_start);
  const grid::OccupancyGrid& robot = run.map;
  result.scans = run.scans;
  result.distance = run.distance;
  result.explored = run.explored;
  int64_t truth_free = 0, known = 0;
  for (size_t i = 0; i < truth.data().size(); ++i) {
    if (truth.data()[i] != grid::kFreeValue) continue;
    ++truth_free;
    known += robot.data()[i] != grid::kUnknownValue;
  }
  result.observed_free = truth_free > 0 ? static_cast<double>(known) / truth_free : 0.0;

  report("vectorizing");
  const Clock::time_point vectorize_start = Clock::now();
  FLEETMAP_ASSIGN_OR_RETURN(const Vectorized robot_vector, Vectorize(robot, options.line_refit));
  result.seconds_vectorize = SecondsSince(vectorize_start);
  FLEETMAP_ASSIGN_OR_RETURN(const Vectorized truth_vector, Vectorize(truth, options.line_refit));
  result.vertices = robot_vector.tiled.ObstacleVertexCount();
  result.segments = robot_vector.tiled.ObstacleSegmentCount();
  result.truth_vmap = truth_vector.vmap.size();

  report("measuring");
  FLEETMAP_ASSIGN_OR_RETURN(const metrics::GridSizes grid_sizes, metrics::MeasureGridSizes(robot));
  result.grid = grid_sizes.cells;
  result.grid_png = grid_sizes.png;
  FLEETMAP_ASSIGN_OR_RETURN(result.vmap, metrics::MeasureBytes(Bytes(robot_vector.vmap)));
  vector_map::TiledVectorMap obstacles_only = robot_vector.tiled;
  for (auto& [tile, map] : obstacles_only.tiles) map.free_space.clear();
  FLEETMAP_ASSIGN_OR_RETURN(const std::string obstacles_vmap,
                            transport::EncodeVmap(obstacles_only));
  FLEETMAP_ASSIGN_OR_RETURN(result.vmap_obstacles, metrics::MeasureBytes(Bytes(obstacles_vmap)));
  // The terrain's grid starts at the origin, so a tile of the terrain's size holds all of it.
  const double terrain_extent = std::max(robot.width(), robot.height()) * robot.resolution();
  FLEETMAP_ASSIGN_OR_RETURN(
      const Vectorized one_tile,
      Vectorize(robot, options.line_refit, /*free_space=*/false, terrain_extent));
  result.vmap_obstacles_one_tile = one_tile.vmap.size();
  FLEETMAP_ASSIGN_OR_RETURN(result.tile_bytes.vector, MeasureVectorTileBytes(robot_vector.tiled));
  FLEETMAP_ASSIGN_OR_RETURN(
      result.tile_bytes.grid,
      MeasureTiledGridBytes(robot, Transform2::Identity(), robot_vector.tiled.tile_size));

  const vector_map::VectorMap robot_merged = robot_vector.tiled.Merged();
  const vector_map::VectorMap truth_merged = truth_vector.tiled.Merged();
  const vector_map::Rasterizer rasterizer;
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid robot_back,
                            rasterizer.Rasterize(robot_merged, truth));
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid truth_back,
                            rasterizer.Rasterize(truth_merged, truth));
  FLEETMAP_ASSIGN_OR_RETURN(result.robot, metrics::CompareMaps(robot, truth));
  FLEETMAP_ASSIGN_OR_RETURN(result.robot_vector, metrics::CompareMaps(robot_back, truth));
  FLEETMAP_ASSIGN_OR_RETURN(result.truth_vector, metrics::CompareMaps(truth_back, truth));
  for (size_t i = 0; i < truth.data().size(); ++i) {
    const grid::CellState t = grid::StateOf(truth.data()[i]);
    const grid::CellState a = grid::StateOf(robot.data()[i]);
    const grid::CellState b = grid::StateOf(robot_back.data()[i]);
    if (a == t && b != t) ++result.lost[static_cast<int>(a)][static_cast<int>(b)];
    if (a != t && b == t) ++result.gained;
  }

  if (!options.image_dir.empty()) {
    report("writing images");
    const std::string stem = options.image_dir + "/" +
                             std::string(sim::TerrainKindName(options.kind)) + "_" +
                             std::to_string(static_cast<int>(options.size));
    vector_map::VectorPngOptions png_options;
    png_options.pixels_per_cell = truth.width() > 1000 ? 1 : 2;
    png_options.draw_vertices = truth.width() <= 1000;
    FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> truth_png,
                              vector_map::EncodeGridPng(truth));
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(stem + "_truth.png", truth_png));
    FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> robot_png,
                              vector_map::EncodeGridPng(robot));
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(stem + "_robot.png", robot_png));
    FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> robot_vector_png,
                              vector_map::RenderVectorMapPng(robot_merged, robot, png_options));
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(stem + "_robot_vector.png", robot_vector_png));
    FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> truth_vector_png,
                              vector_map::RenderVectorMapPng(truth_merged, truth, png_options));
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(stem + "_truth_vector.png", truth_vector_png));
    FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(robot, stem + "_robot.yaml"));
  }
  result.seconds_total = SecondsSince(start);
  return result;
}

}  // namespace fleetmap::bench
