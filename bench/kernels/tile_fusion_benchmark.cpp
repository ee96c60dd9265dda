// The server's fusion alone, without DDS, a store or a queue: what one robot tile update costs
// TileFusion on the load `fleetmap bench capacity` plays (issue 32). A simulated 40 m office is
// revealed column by column in 24 steps and vectorized into 10 m tiles at each step; eight robots,
// each its own participant and each at its own phase, replay it, so every tile has eight
// contributors. One iteration is one robot's update: its changed tiles, then FuseChanged() (trust
// review, fusion, vectorization). The figure to read is the time per tile update:
//
//   build/bench/kernels/tile_fusion_benchmark --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

#include "common/fusion/tile_fusion.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap {
namespace {

constexpr int kRobots = 8;
constexpr int kSteps = 24;

// Per step, the tiles whose geometry changed since the step before (as the capacity benchmark
// records its stream).
std::vector<std::map<TileId, vector_map::VectorMap>> RecordOffice() {
  sim::TerrainOptions terrain;
  terrain.kind = sim::TerrainKind::kOffice;
  terrain.size = 40.0;
  terrain.seed = 1;
  auto generator = sim::TerrainGenerator::Create(terrain);
  const grid::OccupancyGrid building = *sim::RasterizeTerrain(generator->Generate(), 0.05);
  vector_map::TiledVectorizeOptions options;
  options.tile_size = 10.0;
  std::vector<std::map<TileId, vector_map::VectorMap>> steps;
  std::map<TileId, vector_map::VectorMap> previous;
  for (int step = 0; step < kSteps; ++step) {
    grid::OccupancyGrid known = building;
    const int known_columns = building.width() * (step + 1) / kSteps;
    for (int y = 0; y < known.height(); ++y) {
      for (int x = known_columns; x < known.width(); ++x) known.at(x, y) = grid::kUnknownValue;
    }
    auto tiled = vector_map::VectorizeTiled(known, Transform2::Identity(), options);
    std::map<TileId, vector_map::VectorMap> changed;
    for (auto& [tile, map] : tiled->tiles) {
      const auto before = previous.find(tile);
      if (before == previous.end() ||
          before->second.ObstacleVertexCount() != map.ObstacleVertexCount() ||
          before->second.FreeVertexCount() != map.FreeVertexCount()) {
        changed[tile] = map;
      }
    }
    previous = std::move(tiled->tiles);
    steps.push_back(std::move(changed));
  }
  return steps;
}

// "robot3", "p3": spelled out, as GCC 12 warns wrongly (-Wrestrict) about string + to_string.
std::string Named(const char* prefix, int index) {
  std::string name(prefix);
  name.append(std::to_string(index));
  return name;
}

void BM_RobotUpdates(benchmark::State& state) {
  static const auto* const steps =
      new std::vector<std::map<TileId, vector_map::VectorMap>>(RecordOffice());
  auto fusion = fusion::TileFusion::Create(fusion::FusionOptions{});
  if (!fusion.ok()) {
    state.SkipWithError(fusion.status().message().c_str());
    return;
  }
  for (int robot = 0; robot < kRobots; ++robot) {
    fusion->SetRobotSource(RobotId{Named("robot", robot)}, Named("p", robot));
  }
  Timestamp now = std::chrono::system_clock::now();
  int update = 0;
  size_t tiles = 0;
  // One robot's update after another, as staggered robots send them (1 s per robot).
  const auto next = [&] {
    const int robot = update % kRobots;
    const int step = (robot * kSteps / kRobots + update / kRobots) % kSteps;
    ++update;
    now += std::chrono::milliseconds(1000 / kRobots);
    const RobotId id{Named("robot", robot)};
    for (const auto& [tile, map] : (*steps)[static_cast<size_t>(step)]) {
      (void)fusion->UpdateRobotTile(id, tile, map, now);
      ++tiles;
    }
    benchmark::DoNotOptimize(fusion->FuseChanged());
  };
  // Two rounds of the building first: every tile has its eight contributors, corroborated.
  for (int warm = 0; warm < 2 * kSteps * kRobots; ++warm) next();
  tiles = 0;
  for (auto _ : state) next();
  state.counters["tile_updates"] = static_cast<double>(tiles);
  state.counters["per_tile_update"] = benchmark::Counter(
      static_cast<double>(tiles), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_RobotUpdates)->Unit(benchmark::kMillisecond)->MinTime(5.0);

}  // namespace
}  // namespace fleetmap
