#include "common/metrics/map_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace fleetmap::metrics {
namespace {

using grid::CellState;
using grid::OccupancyGrid;

Status CheckComparable(const OccupancyGrid& robot, const OccupancyGrid& truth,
                       const QualityOptions& options) {
  if (robot.width() != truth.width() || robot.height() != truth.height()) {
    return InvalidArgumentError("map quality: robot map is " + std::to_string(robot.width()) +
                                " x " + std::to_string(robot.height()) + ", ground truth " +
                                std::to_string(truth.width()) + " x " +
                                std::to_string(truth.height()));
  }
  if (std::abs(robot.resolution() - truth.resolution()) > 1e-9 * truth.resolution() ||
      std::abs(robot.origin().x - truth.origin().x) > 1e-9 ||
      std::abs(robot.origin().y - truth.origin().y) > 1e-9 ||
      std::abs(robot.origin().yaw - truth.origin().yaw) > 1e-9) {
    return InvalidArgumentError("map quality: robot map and ground truth differ in frame");
  }
  if (options.window_width < 1 || options.window_height < 1) {
    return InvalidArgumentError("map quality: search window must be at least 1 x 1");
  }
  return Status::Ok();
}

std::vector<CellState> States(const OccupancyGrid& grid, const grid::StateThresholds& t) {
  std::vector<CellState> states(grid.data().size());
  std::transform(grid.data().begin(), grid.data().end(), states.begin(),
                 [&](int8_t v) { return grid::StateOf(v, t); });
  return states;
}

double Value(CellState state) {
  switch (state) {
    case CellState::kOccupied:
      return 1.0;
    case CellState::kFree:
      return 0.0;
    case CellState::kUnknown:
      return 0.5;
  }
  return 0.5;
}

std::optional<double> MapScoreOf(const std::vector<CellState>& r, const std::vector<CellState>& g) {
  if (r.empty()) return std::nullopt;
  int64_t same = 0;
  for (size_t i = 0; i < r.size(); ++i) same += r[i] == g[i];
  return 100.0 * static_cast<double>(same) / static_cast<double>(r.size());
}

// 100 * (mean(ab) - mean(a) mean(b)) / (std(a) std(b)), population statistics.
template <typename F>
std::optional<double> Correlation(const std::vector<CellState>& r, const std::vector<CellState>& g,
                                  F&& value) {
  const double n = static_cast<double>(r.size());
  if (r.empty()) return std::nullopt;
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (size_t i = 0; i < r.size(); ++i) {
    const double a = value(r[i]);
    const double b = value(g[i]);
    sa += a;
    sb += b;
    saa += a * a;
    sbb += b * b;
    sab += a * b;
  }
  const double ma = sa / n;
  const double mb = sb / n;
  const double va = saa / n - ma * ma;
  const double vb = sbb / n - mb * mb;
  constexpr double kTiny = 1e-12;
  if (va <= kTiny || vb <= kTiny) return std::nullopt;
  return 100.0 * (sab / n - ma * mb) / std::sqrt(va * vb);
}

// OPDF / UPDF: for every cell of R in `state`, the Manhattan distance to the nearest cell of G in
// `state` within the window, or r. Row pass: nearest |dx| in the same row (bounded by half the
// window width); column pass: min over |dy| <= half height of row[y + dy] + |dy|. O(n + m * h).
std::optional<double> PictureDistance(const std::vector<CellState>& r,
                                      const std::vector<CellState>& g, int width, int height,
                                      CellState state, const QualityOptions& options) {
  const int half_w = options.window_width / 2;
  const int half_h = options.window_height / 2;
  const double penalty = std::hypot(options.window_width, options.window_height);
  constexpr int kNone = std::numeric_limits<int>::max() / 4;
  std::vector<int> row_distance(r.size(), kNone);
  for (int y = 0; y < height; ++y) {
    const size_t base = static_cast<size_t>(y) * width;
    int last = -kNone;
    for (int x = 0; x < width; ++x) {
      if (g[base + x] == state) last = x;
      if (x - last <= half_w) row_distance[base + x] = x - last;
    }
    last = kNone;
    for (int x = width - 1; x >= 0; --x) {
      if (g[base + x] == state) last = x;
      if (last - x <= half_w) row_distance[base + x] = std::min(row_distance[base + x], last - x);
    }
  }
  int64_t count = 0;
  double sum = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (r[static_cast<size_t>(y) * width + x] != state) continue;
      ++count;
      int best = kNone;
      const int y_lo = std::max(0, y - half_h);
      const int y_hi = std::min(height - 1, y + half_h);
      for (int yy = y_lo; yy <= y_hi; ++yy) {
        best = std::min(best, row_distance[static_cast<size_t>(yy) * width + x] + std::abs(yy - y));
      }
      sum += best >= kNone ? penalty : best;
    }
  }
  if (count == 0) return std::nullopt;
  return 100.0 * (1.0 - sum / (static_cast<double>(count) * penalty));
}

}  // namespace

StatusOr<QualityScores> CompareMaps(const OccupancyGrid& robot, const OccupancyGrid& truth,
                                    const QualityOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(CheckComparable(robot, truth, options));
  const auto r = States(robot, options.thresholds);
  const auto g = States(truth, options.thresholds);
  QualityScores scores;
  scores.map_score = MapScoreOf(r, g);
  scores.cross_correlation = Correlation(r, g, Value);
  scores.pearson_occupied =
      Correlation(r, g, [](CellState s) { return s == CellState::kOccupied ? 1.0 : 0.0; });
  scores.occupied_picture_distance =
      PictureDistance(r, g, robot.width(), robot.height(), CellState::kOccupied, options);
  scores.unoccupied_picture_distance =
      PictureDistance(r, g, robot.width(), robot.height(), CellState::kFree, options);
  return scores;
}

StatusOr<std::optional<double>> MapScore(const OccupancyGrid& robot, const OccupancyGrid& truth,
                                         const QualityOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(CheckComparable(robot, truth, options));
  return MapScoreOf(States(robot, options.thresholds), States(truth, options.thresholds));
}

StatusOr<std::optional<double>> CrossCorrelation(const OccupancyGrid& robot,
                                                 const OccupancyGrid& truth,
                                                 const QualityOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(CheckComparable(robot, truth, options));
  return Correlation(States(robot, options.thresholds), States(truth, options.thresholds), Value);
}

StatusOr<std::optional<double>> PearsonOccupied(const OccupancyGrid& robot,
                                                const OccupancyGrid& truth,
                                                const QualityOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(CheckComparable(robot, truth, options));
  return Correlation(States(robot, options.thresholds), States(truth, options.thresholds),
                     [](CellState s) { return s == CellState::kOccupied ? 1.0 : 0.0; });
}

StatusOr<std::optional<double>> OccupiedPictureDistance(const OccupancyGrid& robot,
                                                        const OccupancyGrid& truth,
                                                        const QualityOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(CheckComparable(robot, truth, options));
  return PictureDistance(States(robot, options.thresholds), States(truth, options.thresholds),
                         robot.width(), robot.height(), CellState::kOccupied, options);
}

StatusOr<std::optional<double>> UnoccupiedPictureDistance(const OccupancyGrid& robot,
                                                          const OccupancyGrid& truth,
                                                          const QualityOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(CheckComparable(robot, truth, options));
  return PictureDistance(States(robot, options.thresholds), States(truth, options.thresholds),
                         robot.width(), robot.height(), CellState::kFree, options);
}

}  // namespace fleetmap::metrics
