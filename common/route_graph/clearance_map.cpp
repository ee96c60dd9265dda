#include "common/route_graph/clearance_map.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "common/core/check.hpp"

namespace fleetmap::route_graph {
namespace {

constexpr double kHalfDiagonal = 0.70710678118654752;

}  // namespace

ClearanceMap::ClearanceMap(const grid::OccupancyGrid& grid, double cap,
                           const grid::StateThresholds& thresholds)
    : width_(grid.width()),
      height_(grid.height()),
      resolution_(grid.resolution()),
      cap_(cap),
      origin_(grid.origin().x, grid.origin().y),
      thresholds_(thresholds),
      clearance_(static_cast<size_t>(grid.cell_count()), 0.0F) {
  FLEETMAP_CHECK(cap > 0.0, "ClearanceMap needs a positive cap");
  Update(grid, grid::CellRect{0, 0, width_, height_});
}

void ClearanceMap::Update(const grid::OccupancyGrid& grid, const grid::CellRect& rect) {
  FLEETMAP_CHECK(grid.width() == width_ && grid.height() == height_,
                 "ClearanceMap::Update with a grid of another size");
  const int x0 = std::max(rect.x0, 0);
  const int y0 = std::max(rect.y0, 0);
  const int x1 = std::min(rect.x0 + rect.width, width_);
  const int y1 = std::min(rect.y0 + rect.height, height_);
  if (x0 >= x1 || y0 >= y1) return;
  // Every blocked cell within the cap of the rectangle, plus one ring: a cell further away cannot
  // be a nearer obstacle than the cap. Cells outside the grid are blocked.
  const int reach = static_cast<int>(std::ceil(cap_ / resolution_)) + 2;
  const int wx0 = x0 - reach;
  const int wy0 = y0 - reach;
  const int ww = (x1 - x0) + 2 * reach;
  const int wh = (y1 - y0) + 2 * reach;
  cv::Mat free_mask(wh, ww, CV_8UC1);
  for (int wy = 0; wy < wh; ++wy) {
    uint8_t* row = free_mask.ptr<uint8_t>(wy);
    const int y = wy0 + wy;
    for (int wx = 0; wx < ww; ++wx) {
      const int x = wx0 + wx;
      const bool free =
          grid.Contains(x, y) && grid.StateAt(x, y, thresholds_) == grid::CellState::kFree;
      row[wx] = free ? 255 : 0;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(free_mask, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  for (int y = y0; y < y1; ++y) {
    const float* row = distance.ptr<float>(y - wy0);
    for (int x = x0; x < x1; ++x) {
      const float cells = row[x - wx0];
      float value = 0.0F;
      if (cells > 0.0F) {
        value =
            static_cast<float>(std::min(cells * resolution_ - kHalfDiagonal * resolution_, cap_));
      }
      clearance_[static_cast<size_t>(y) * width_ + x] = value;
    }
  }
}

grid::CellIndex ClearanceMap::CellOf(const Point2& point) const {
  return {static_cast<int>(std::floor((point.x() - origin_.x()) / resolution_)),
          static_cast<int>(std::floor((point.y() - origin_.y()) / resolution_))};
}

double ClearanceMap::PointBound(const Point2& point, double enough) const {
  // The distance to an obstacle is 1-Lipschitz: a cell's bound minus the distance from its centre
  // bounds the point. The best of the 3 x 3 cells around the point's cell.
  const grid::CellIndex cell = CellOf(point);
  double best = -1.0;
  // The point's own cell first: in open space it alone is enough.
  if (Contains(cell.x, cell.y) && at(cell.x, cell.y) > 0.0F) {
    best = at(cell.x, cell.y) - (point - CellCenter(cell.x, cell.y)).norm();
    if (best >= enough) return best;
  }
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int x = cell.x + dx;
      const int y = cell.y + dy;
      if ((dx == 0 && dy == 0) || !Contains(x, y)) continue;
      const float value = at(x, y);
      // A neighbour's centre is at least half a cell from the point.
      if (value <= 0.0F || value - 0.5 * resolution_ <= best) continue;
      best = std::max(best, value - (point - CellCenter(x, y)).norm());
      if (best >= enough) return best;
    }
  }
  return best;
}

template <typename Visit>
bool ClearanceMap::WalkSegment(const Point2& a, const Point2& b, double enough,
                               Visit&& visit) const {
  const double step = resolution_ / 4.0;
  const double length = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / step)));
  // A point between two samples is at most half a step from one of them.
  const double slack = 0.5 * length / steps;
  for (int i = 0; i <= steps; ++i) {
    const Point2 point = a + (b - a) * (static_cast<double>(i) / steps);
    if (!visit(PointBound(point, enough + slack) - slack)) return false;
  }
  return true;
}

double ClearanceMap::SegmentClearance(const Point2& a, const Point2& b) const {
  double lowest = cap_;
  WalkSegment(a, b, cap_, [&lowest](double bound) {
    lowest = std::min(lowest, bound);
    return true;
  });
  return lowest;
}

bool ClearanceMap::SegmentKeeps(const Point2& a, const Point2& b, double required) const {
  return WalkSegment(a, b, required, [required](double bound) { return bound >= required; });
}

}  // namespace fleetmap::route_graph
