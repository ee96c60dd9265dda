#include "common/sim/start_poses.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

namespace fleetmap::sim {
namespace {

// Distance in cells from every cell to the nearest non-free cell (8-connected BFS, chamfer-ish).
std::vector<int> ClearanceCells(const grid::OccupancyGrid& truth) {
  const int width = truth.width();
  const int height = truth.height();
  std::vector<int> distance(static_cast<size_t>(width) * height, std::numeric_limits<int>::max());
  std::deque<int> queue;
  for (int i = 0; i < width * height; ++i) {
    if (truth.data()[i] != grid::kFreeValue) {
      distance[i] = 0;
      queue.push_back(i);
    }
  }
  while (!queue.empty()) {
    const int index = queue.front();
    queue.pop_front();
    const int x = index % width;
    const int y = index / width;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx;
        const int ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
        const int next = ny * width + nx;
        if (distance[next] > distance[index] + 1) {
          distance[next] = distance[index] + 1;
          queue.push_back(next);
        }
      }
    }
  }
  return distance;
}

}  // namespace

StatusOr<std::vector<Pose2>> SpreadStarts(const grid::OccupancyGrid& truth, const Pose2& first,
                                          int count, double clearance) {
  if (count < 1) return InvalidArgumentError("a fleet needs at least one robot");
  const std::vector<int> clear = ClearanceCells(truth);
  const int needed = static_cast<int>(std::ceil(clearance / truth.resolution()));
  // Candidates on a lattice coarse enough to keep the sampling cheap for large fleets on large
  // terrains (about 20 000 cells), fine enough to find room in narrow ones.
  constexpr int64_t kMaxCandidates = 20000;
  const int stride = std::max<int>(
      1, static_cast<int>(
             std::ceil(std::sqrt(static_cast<double>(truth.cell_count()) / kMaxCandidates))));
  std::vector<grid::CellIndex> candidates;
  for (int y = 0; y < truth.height(); y += stride) {
    for (int x = 0; x < truth.width(); x += stride) {
      if (clear[static_cast<size_t>(y) * truth.width() + x] >= needed) candidates.push_back({x, y});
    }
  }
  if (candidates.empty()) {
    return InvalidArgumentError("no free cell lies " + std::to_string(clearance) +
                                " m from every obstacle");
  }
  std::vector<Pose2> starts = {first};
  // Squared distance (cells) from each candidate to the nearest chosen start.
  std::vector<double> nearest(candidates.size(), std::numeric_limits<double>::max());
  while (static_cast<int>(starts.size()) < count) {
    const Pose2& last = starts.back();
    size_t best = 0;
    for (size_t i = 0; i < candidates.size(); ++i) {
      const Point2 centre = truth.CellCenter(candidates[i].x, candidates[i].y);
      nearest[i] = std::min(nearest[i], (centre - last.translation()).squaredNorm());
      if (nearest[i] > nearest[best]) best = i;
    }
    const Point2 centre = truth.CellCenter(candidates[best].x, candidates[best].y);
    starts.push_back(Pose2{centre.x(), centre.y(), 0.0});
  }
  return starts;
}

}  // namespace fleetmap::sim
