#include "common/extrapolation/patch_image.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>

namespace fleetmap::extrapolation {

PatchImage::PatchImage(const std::vector<Point2>& coordinates, double cell) : cell_(cell) {
  if (coordinates.empty()) return;
  double max_a = coordinates[0].x(), max_b = coordinates[0].y();
  min_a_ = max_a;
  min_b_ = max_b;
  for (const Point2& c : coordinates) {
    min_a_ = std::min(min_a_, c.x());
    min_b_ = std::min(min_b_, c.y());
    max_a = std::max(max_a, c.x());
    max_b = std::max(max_b, c.y());
  }
  // Bounded: points come from a sensor of a few metres' range; cap the image all the same.
  constexpr int kMaxSide = 4000;
  width_ = std::min(kMaxSide, static_cast<int>((max_a - min_a_) / cell_) + 1);
  height_ = std::min(kMaxSide, static_cast<int>((max_b - min_b_) / cell_) + 1);
  points_in_cell_.resize(static_cast<size_t>(width_) * height_);
  cell_of_point_.reserve(coordinates.size());
  for (size_t i = 0; i < coordinates.size(); ++i) {
    const int index = Index(CellX(coordinates[i].x()), CellY(coordinates[i].y()));
    cell_of_point_.push_back(index);
    points_in_cell_[index].push_back(static_cast<int>(i));
  }
}

int PatchImage::CellX(double a) const {
  return std::clamp(static_cast<int>((a - min_a_) / cell_), 0, width_ - 1);
}
int PatchImage::CellY(double b) const {
  return std::clamp(static_cast<int>((b - min_b_) / cell_), 0, height_ - 1);
}

std::vector<std::vector<int>> PatchImage::Components() const {
  std::vector<std::vector<int>> components;
  std::vector<uint8_t> seen(points_in_cell_.size(), 0);
  for (size_t start = 0; start < points_in_cell_.size(); ++start) {
    if (seen[start] || points_in_cell_[start].empty()) continue;
    std::vector<int> points;
    std::deque<int> queue = {static_cast<int>(start)};
    seen[start] = 1;
    while (!queue.empty()) {
      const int c = queue.front();
      queue.pop_front();
      points.insert(points.end(), points_in_cell_[c].begin(), points_in_cell_[c].end());
      const int x = c % width_, y = c / width_;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
          const int n = Index(nx, ny);
          if (!seen[n] && !points_in_cell_[n].empty()) {
            seen[n] = 1;
            queue.push_back(n);
          }
        }
      }
    }
    std::sort(points.begin(), points.end());
    components.push_back(std::move(points));
  }
  std::stable_sort(components.begin(), components.end(),
                   [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return components;
}

int PatchImage::CellCount(const std::vector<int>& indices) const {
  std::set<int> cells;
  for (int i : indices) cells.insert(cell_of_point_[i]);
  return static_cast<int>(cells.size());
}

bool PatchImage::Occupied(const Point2& p, int radius_cells) const {
  const int cx = static_cast<int>(std::floor((p.x() - min_a_) / cell_));
  const int cy = static_cast<int>(std::floor((p.y() - min_b_) / cell_));
  for (int y = cy - radius_cells; y <= cy + radius_cells; ++y) {
    for (int x = cx - radius_cells; x <= cx + radius_cells; ++x) {
      if (x < 0 || y < 0 || x >= width_ || y >= height_) continue;
      if (!points_in_cell_[Index(x, y)].empty()) return true;
    }
  }
  return false;
}

}  // namespace fleetmap::extrapolation
