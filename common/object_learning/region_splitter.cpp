#include "common/object_learning/region_splitter.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace fleetmap::object_learning {
namespace {

// A region drawn into a local box with a one-cell border of 0, for erosion and flood fills.
class LocalMask {
 public:
  explicit LocalMask(const std::vector<grid::CellIndex>& cells) {
    x0_ = y0_ = std::numeric_limits<int>::max();
    int x1 = std::numeric_limits<int>::min(), y1 = std::numeric_limits<int>::min();
    for (const grid::CellIndex& c : cells) {
      x0_ = std::min(x0_, c.x);
      y0_ = std::min(y0_, c.y);
      x1 = std::max(x1, c.x);
      y1 = std::max(y1, c.y);
    }
    x0_ -= 1;
    y0_ -= 1;
    width_ = x1 - x0_ + 2;
    height_ = y1 - y0_ + 2;
    label_.assign(static_cast<size_t>(width_) * height_, 0);
    for (const grid::CellIndex& c : cells) at(c.x - x0_, c.y - y0_) = 1;
  }
  int width() const { return width_; }
  int height() const { return height_; }
  int& at(int x, int y) { return label_[static_cast<size_t>(y) * width_ + x]; }
  int at(int x, int y) const { return label_[static_cast<size_t>(y) * width_ + x]; }
  grid::CellIndex Global(int x, int y) const { return {x + x0_, y + y0_}; }
  const std::vector<int>& labels() const { return label_; }
  std::vector<int>& labels() { return label_; }

 private:
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::vector<int> label_;
};

// 8-connected components of the cells of `mask` equal to `value`, as local coordinates.
std::vector<std::vector<grid::CellIndex>> Components(const LocalMask& mask, int value) {
  std::vector<uint8_t> seen(mask.labels().size(), 0);
  std::vector<std::vector<grid::CellIndex>> out;
  std::vector<grid::CellIndex> stack;
  const int w = mask.width(), h = mask.height();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (mask.at(x, y) != value || seen[i]) continue;
      std::vector<grid::CellIndex> component;
      seen[i] = 1;
      stack.push_back({x, y});
      while (!stack.empty()) {
        const grid::CellIndex c = stack.back();
        stack.pop_back();
        component.push_back(c);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = c.x + dx, ny = c.y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            const size_t j = static_cast<size_t>(ny) * w + nx;
            if (seen[j] || mask.at(nx, ny) != value) continue;
            seen[j] = 1;
            stack.push_back({nx, ny});
          }
        }
      }
      out.push_back(std::move(component));
    }
  }
  return out;
}

bool Fits(const std::vector<grid::CellIndex>& cells, const RegionLimits& limits) {
  return static_cast<int>(cells.size()) <= limits.max_cells &&
         RegionRadius(cells) <= limits.max_radius_cells;
}

// Step 2: erode until the part falls apart into cores of a few cells, then grow the cores back
// inside the part (breadth-first: each cell to the nearest core). Empty when it never falls apart.
std::vector<std::vector<grid::CellIndex>> SplitAtNecks(const std::vector<grid::CellIndex>& cells) {
  const LocalMask original(cells);
  LocalMask eroded = original;
  const int w = eroded.width(), h = eroded.height();
  for (int round = 0; round < 64; ++round) {
    LocalMask next = eroded;
    bool any = false;
    for (int y = 1; y + 1 < h; ++y) {
      for (int x = 1; x + 1 < w; ++x) {
        if (!eroded.at(x, y)) continue;
        bool keep = true;
        for (int dy = -1; dy <= 1 && keep; ++dy) {
          for (int dx = -1; dx <= 1 && keep; ++dx) keep = eroded.at(x + dx, y + dy) != 0;
        }
        next.at(x, y) = keep ? 1 : 0;
        any = any || keep;
      }
    }
    if (!any) return {};
    eroded = std::move(next);
    std::vector<std::vector<grid::CellIndex>> cores = Components(eroded, 1);
    // Cores of fewer than 3 cells are corners left by erosion, not objects.
    cores.erase(
        std::remove_if(cores.begin(), cores.end(), [](const auto& c) { return c.size() < 3; }),
        cores.end());
    if (cores.size() < 2) continue;
    // Geodesic watershed: labels 2.. for the cores, spread through the original part.
    LocalMask labels = original;
    std::deque<grid::CellIndex> queue;
    for (size_t k = 0; k < cores.size(); ++k) {
      for (const grid::CellIndex& c : cores[k]) {
        labels.at(c.x, c.y) = static_cast<int>(k) + 2;
        queue.push_back(c);
      }
    }
    while (!queue.empty()) {
      const grid::CellIndex c = queue.front();
      queue.pop_front();
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = c.x + dx, ny = c.y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h || labels.at(nx, ny) != 1) continue;
          labels.at(nx, ny) = labels.at(c.x, c.y);
          queue.push_back({nx, ny});
        }
      }
    }
    std::vector<std::vector<grid::CellIndex>> parts(cores.size());
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const int l = labels.at(x, y);
        if (l >= 2) parts[l - 2].push_back(labels.Global(x, y));
      }
    }
    return parts;
  }
  return {};
}

// Step 3: slices across the long axis (principal axis of the cells), each within the limits.
std::vector<std::vector<grid::CellIndex>> Slice(const std::vector<grid::CellIndex>& cells,
                                                const RegionLimits& limits) {
  const double n = static_cast<double>(cells.size());
  double mx = 0.0, my = 0.0;
  for (const grid::CellIndex& c : cells) mx += c.x, my += c.y;
  mx /= n;
  my /= n;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const grid::CellIndex& c : cells) {
    sxx += (c.x - mx) * (c.x - mx);
    sxy += (c.x - mx) * (c.y - my);
    syy += (c.y - my) * (c.y - my);
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const double ux = std::cos(angle), uy = std::sin(angle);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const grid::CellIndex& c : cells) {
    const double t = (c.x - mx) * ux + (c.y - my) * uy;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  // Enough slices for the cell count and for the radius along the axis.
  const int by_cells = static_cast<int>(std::ceil(n / limits.max_cells));
  const int by_length =
      static_cast<int>(std::ceil((hi - lo + 1.0) / (1.4 * limits.max_radius_cells)));
  const int count = std::max({2, by_cells, by_length});
  std::vector<std::vector<grid::CellIndex>> parts(count);
  for (const grid::CellIndex& c : cells) {
    const double t = (c.x - mx) * ux + (c.y - my) * uy;
    const int k = std::clamp(static_cast<int>((t - lo) / (hi - lo + 1e-9) * count), 0, count - 1);
    parts[k].push_back(c);
  }
  parts.erase(std::remove_if(parts.begin(), parts.end(), [](const auto& p) { return p.empty(); }),
              parts.end());
  return parts;
}

void Split(const std::vector<grid::CellIndex>& cells, const RegionLimits& limits, int depth,
           SplitRegions* out) {
  if (Fits(cells, limits)) {
    out->parts.push_back(cells);
    return;
  }
  const LocalMask mask(cells);
  std::vector<std::vector<grid::CellIndex>> components = Components(mask, 1);
  if (components.size() >= 2) {
    for (std::vector<grid::CellIndex>& component : components) {
      for (grid::CellIndex& c : component) c = mask.Global(c.x, c.y);
      Split(component, limits, depth + 1, out);
    }
    return;
  }
  std::vector<std::vector<grid::CellIndex>> parts = SplitAtNecks(cells);
  if (parts.size() < 2 || depth > 16) {
    parts = Slice(cells, limits);
    out->sliced = true;
    if (depth > 16) {
      for (std::vector<grid::CellIndex>& part : parts) out->parts.push_back(std::move(part));
      return;
    }
  }
  for (const std::vector<grid::CellIndex>& part : parts) Split(part, limits, depth + 1, out);
}

}  // namespace

double RegionRadius(const std::vector<grid::CellIndex>& cells) {
  if (cells.empty()) return 0.0;
  double sx = 0.0, sy = 0.0;
  for (const grid::CellIndex& c : cells) sx += c.x, sy += c.y;
  const double n = static_cast<double>(cells.size());
  const int cx = static_cast<int>(std::lround(sx / n)), cy = static_cast<int>(std::lround(sy / n));
  double radius = 0.0;
  for (const grid::CellIndex& c : cells) radius = std::max(radius, std::hypot(c.x - cx, c.y - cy));
  return radius;
}

SplitRegions SplitRegion(const std::vector<grid::CellIndex>& cells, const RegionLimits& limits) {
  SplitRegions out;
  if (!cells.empty()) Split(cells, limits, 0, &out);
  return out;
}

}  // namespace fleetmap::object_learning
