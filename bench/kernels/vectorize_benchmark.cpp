// Vectorization kernels on the real maps (../shared/data/maps): fleetmap's default method, the
// paper's greedy method, and the OpenCV baseline of SOURCES.md (findContours(RETR_LIST,
// CHAIN_APPROX_SIMPLE) on occupied cells + approxPolyDP(1.414 cells)). Obstacles only (no free
// space) so that the three do the same job. Counters: vertices (and segments) of the output.
//
//   build/bench/kernels/vectorize_benchmark --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "bench/kernels/real_maps.hpp"
#include "common/vector_map/vectorizer.hpp"

namespace fleetmap::vector_map {
namespace {

void BM_Vectorize(benchmark::State& state, const std::string& name, VectorizeMethod method,
                  bool refit_lines) {
  const grid::OccupancyGrid* grid = bench::LoadRealMap(name);
  if (grid == nullptr) {
    state.SkipWithError("cannot load map");
    return;
  }
  VectorizerOptions options;
  options.method = method;
  options.extract_free_space = false;
  options.refit_lines = refit_lines;
  const Vectorizer vectorizer(options);
  size_t vertices = 0;
  size_t segments = 0;
  for (auto _ : state) {
    auto map = vectorizer.Vectorize(*grid);
    benchmark::DoNotOptimize(map);
    vertices = map->ObstacleVertexCount();
    segments = map->ObstacleSegmentCount();
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["segments"] = static_cast<double>(segments);
  state.counters["cells"] = static_cast<double>(grid->cell_count());
}

void BM_OpenCv(benchmark::State& state, const std::string& name) {
  const grid::OccupancyGrid* grid = bench::LoadRealMap(name);
  if (grid == nullptr) {
    state.SkipWithError("cannot load map");
    return;
  }
  cv::Mat mask(grid->height(), grid->width(), CV_8UC1);
  for (int y = 0; y < grid->height(); ++y) {
    for (int x = 0; x < grid->width(); ++x) {
      mask.at<uint8_t>(y, x) = grid->StateAt(x, y) == grid::CellState::kOccupied ? 255 : 0;
    }
  }
  size_t vertices = 0;
  for (auto _ : state) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
    vertices = 0;
    std::vector<cv::Point> simplified;
    for (const auto& contour : contours) {
      cv::approxPolyDP(contour, simplified, 1.414, true);
      vertices += simplified.size();
    }
    benchmark::DoNotOptimize(vertices);
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["cells"] = static_cast<double>(grid->cell_count());
}

const bool kRegistered = [] {
  for (const std::string& name : bench::RealMapNames()) {
    benchmark::RegisterBenchmark(("default/" + name).c_str(), BM_Vectorize, name,
                                 VectorizeMethod::kDefault, true)
        ->Unit(benchmark::kMillisecond);
    // Without line_refit: its time is the difference.
    benchmark::RegisterBenchmark(("default_no_refit/" + name).c_str(), BM_Vectorize, name,
                                 VectorizeMethod::kDefault, false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("paper/" + name).c_str(), BM_Vectorize, name,
                                 VectorizeMethod::kPaper, false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("opencv/" + name).c_str(), BM_OpenCv, name)
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
}  // namespace fleetmap::vector_map
