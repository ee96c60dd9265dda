#include "common/route_graph/skeleton.hpp"

#include <algorithm>
#include <array>

namespace fleetmap::route_graph {
namespace {

// The 8 neighbours counter-clockwise from east: x1..x8 of Yokoi's connectivity number.
constexpr std::array<int, 8> kRingX = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr std::array<int, 8> kRingY = {0, 1, 1, 1, 0, -1, -1, -1};
// The 4 directions a border cell is peeled from: north, east, south, west.
constexpr std::array<int, 4> kSideX = {0, 1, 0, -1};
constexpr std::array<int, 4> kSideY = {1, 0, -1, 0};

grid::CellRect Clip(const grid::CellRect& rect, int width, int height) {
  const int x0 = std::max(rect.x0, 0);
  const int y0 = std::max(rect.y0, 0);
  const int x1 = std::min(rect.x0 + rect.width, width);
  const int y1 = std::min(rect.y0 + rect.height, height);
  return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

}  // namespace

Skeleton::Skeleton(const ClearanceMap& clearance, double required)
    : width_(clearance.width()),
      height_(clearance.height()),
      cells_(static_cast<size_t>(width_) * height_, 0) {
  Update(clearance, required, grid::CellRect{0, 0, width_, height_});
}

void Skeleton::Update(const ClearanceMap& clearance, double required,
                      const grid::CellRect& region) {
  const grid::CellRect clipped = Clip(region, width_, height_);
  if (clipped.empty()) return;
  for (int y = clipped.y0; y < clipped.y0 + clipped.height; ++y) {
    for (int x = clipped.x0; x < clipped.x0 + clipped.width; ++x) {
      cells_[Index(x, y)] = clearance.at(x, y) >= required ? 1 : 0;
    }
  }
  Thin(clipped);
}

bool Skeleton::Deletable(int x, int y) const {
  std::array<int, 8> ring{};
  int neighbours = 0;
  for (int k = 0; k < 8; ++k) {
    ring[k] = at(x + kRingX[k], y + kRingY[k]) ? 1 : 0;
    neighbours += ring[k];
  }
  if (neighbours < 2) return false;  // the end of a curve, or a part of one cell
  // Yokoi's 8-connectivity number over the complements; the cell is simple when it is 1.
  int connectivity = 0;
  for (int k = 0; k < 8; k += 2) {
    const int a = 1 - ring[k];
    const int b = 1 - ring[(k + 1) % 8];
    const int c = 1 - ring[(k + 2) % 8];
    connectivity += a - a * b * c;
  }
  return connectivity == 1;
}

void Skeleton::Thin(const grid::CellRect& region) {
  auto in_region = [&region](int x, int y) { return region.Contains(x, y); };
  std::vector<uint8_t> queued(cells_.size(), 0);
  std::vector<int> candidates;
  for (int y = region.y0; y < region.y0 + region.height; ++y) {
    for (int x = region.x0; x < region.x0 + region.width; ++x) {
      if (!at(x, y)) continue;
      for (int side = 0; side < 4; ++side) {
        if (!at(x + kSideX[side], y + kSideY[side])) {
          candidates.push_back(static_cast<int>(Index(x, y)));
          queued[Index(x, y)] = 1;
          break;
        }
      }
    }
  }
  std::vector<int> deleted;
  std::vector<int> next;
  while (!candidates.empty()) {
    deleted.clear();
    for (int side = 0; side < 4; ++side) {
      for (const int index : candidates) {
        if (cells_[index] == 0) continue;
        const int x = index % width_;
        const int y = index / width_;
        if (at(x + kSideX[side], y + kSideY[side])) continue;
        if (!Deletable(x, y)) continue;
        cells_[index] = 0;
        deleted.push_back(index);
      }
    }
    // A cell is looked at again only when a neighbour went: otherwise nothing it decides on
    // changed.
    for (const int index : candidates) queued[index] = 0;
    next.clear();
    for (const int index : deleted) {
      const int x = index % width_;
      const int y = index / width_;
      for (int k = 0; k < 8; ++k) {
        const int nx = x + kRingX[k];
        const int ny = y + kRingY[k];
        if (!in_region(nx, ny) || !at(nx, ny)) continue;
        const size_t n = Index(nx, ny);
        if (queued[n] != 0) continue;
        queued[n] = 1;
        next.push_back(static_cast<int>(n));
      }
    }
    candidates.swap(next);
  }
}

}  // namespace fleetmap::route_graph
