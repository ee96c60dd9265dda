// The tile codec's cost against the vectorizing it follows (issue 17: encoding + decoding a tile
// costs at most 10 % of vectorizing it). Per real map (../shared/data/maps): vectorize every 10 m
// tile as an agent does (obstacles and free space), then encode and decode every tile as the
// wire does (transport::EncodeTilePayload / DecodeTilePayload: layout 5, zstd when smaller).
// Compare the two rows of a map:
//
//   build/bench/kernels/tile_codec_benchmark --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "bench/kernels/real_maps.hpp"
#include "common/transport/tile_payload.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap {
namespace {

void BM_VectorizeTiles(benchmark::State& state, const std::string& name) {
  const grid::OccupancyGrid* grid = bench::LoadRealMap(name);
  if (grid == nullptr) {
    state.SkipWithError("cannot load map");
    return;
  }
  size_t tiles = 0;
  for (auto _ : state) {
    auto tiled = vector_map::VectorizeTiled(*grid, Transform2::Identity(), {});
    benchmark::DoNotOptimize(tiled);
    tiles = tiled->tiles.size();
  }
  state.counters["tiles"] = static_cast<double>(tiles);
}

void BM_EncodeDecodeTiles(benchmark::State& state, const std::string& name) {
  const grid::OccupancyGrid* grid = bench::LoadRealMap(name);
  if (grid == nullptr) {
    state.SkipWithError("cannot load map");
    return;
  }
  const auto tiled = vector_map::VectorizeTiled(*grid, Transform2::Identity(), {});
  if (!tiled.ok()) {
    state.SkipWithError(tiled.status().message().c_str());
    return;
  }
  std::vector<transport::VectorTileMessage> messages;
  for (const auto& [id, map] : tiled->tiles) {
    transport::VectorTileMessage message;
    message.robot_id = RobotId{"robot0"};
    message.tile = id;
    message.map = map;
    messages.push_back(std::move(message));
  }
  size_t bytes = 0;
  for (auto _ : state) {
    bytes = 0;
    for (const transport::VectorTileMessage& message : messages) {
      auto payload = transport::EncodeTilePayload(message);
      auto back = transport::DecodeTilePayload(*payload, name);
      benchmark::DoNotOptimize(back);
      bytes += payload->size();
    }
  }
  state.counters["tiles"] = static_cast<double>(messages.size());
  state.counters["bytes"] = static_cast<double>(bytes);
}

const bool kRegistered = [] {
  for (const std::string& name : bench::RealMapNames()) {
    benchmark::RegisterBenchmark(("vectorize_tiles/" + name).c_str(), BM_VectorizeTiles, name)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("encode_decode_tiles/" + name).c_str(), BM_EncodeDecodeTiles,
                                 name)
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
}  // namespace fleetmap
