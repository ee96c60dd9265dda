#include "common/object_learning/snapshot_extractor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "common/object_learning/region_splitter.hpp"

namespace fleetmap::object_learning {
namespace {

using Mask = std::vector<uint8_t>;

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Dilation of a mask by a square of side 2 r + 1 (separable: rows, then columns).
Mask Dilate(const Mask& mask, int width, int height, int r) {
  if (r <= 0) return mask;
  Mask rows(mask.size(), 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint8_t any = 0;
      for (int i = std::max(0, x - r); i <= std::min(width - 1, x + r) && !any; ++i) {
        any = mask[static_cast<size_t>(y) * width + i];
      }
      rows[static_cast<size_t>(y) * width + x] = any;
    }
  }
  Mask out(mask.size(), 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint8_t any = 0;
      for (int j = std::max(0, y - r); j <= std::min(height - 1, y + r) && !any; ++j) {
        any = rows[static_cast<size_t>(j) * width + x];
      }
      out[static_cast<size_t>(y) * width + x] = any;
    }
  }
  return out;
}

// Keeps the cells of `mask` whose box mean over (2 r + 1)^2 cells (outside counts as 0) is at
// least `threshold`: the low-pass filter, via a summed-area table.
Mask LowPass(const Mask& mask, int width, int height, int r, double threshold) {
  if (r <= 0) return mask;
  std::vector<int32_t> sat(static_cast<size_t>(width + 1) * (height + 1), 0);
  auto s = [&](int x, int y) -> int32_t& { return sat[static_cast<size_t>(y) * (width + 1) + x]; };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      s(x + 1, y + 1) =
          mask[static_cast<size_t>(y) * width + x] + s(x, y + 1) + s(x + 1, y) - s(x, y);
    }
  }
  const double window = (2.0 * r + 1.0) * (2.0 * r + 1.0);
  Mask out(mask.size(), 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!mask[static_cast<size_t>(y) * width + x]) continue;
      const int x0 = std::max(0, x - r), x1 = std::min(width, x + r + 1);
      const int y0 = std::max(0, y - r), y1 = std::min(height, y + r + 1);
      const int32_t count = s(x1, y1) - s(x0, y1) - s(x1, y0) + s(x0, y0);
      if (count >= threshold * window - 1e-9) out[static_cast<size_t>(y) * width + x] = 1;
    }
  }
  return out;
}

// Separable Gaussian smoothing (standard deviation `sigma` cells, kernel to 3 sigma); outside
// the patch reads as 0.
void Blur(double sigma, scene::Patch* patch) {
  if (sigma <= 0.0) return;
  const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<float> kernel(2 * r + 1);
  float total = 0.0f;
  for (int i = -r; i <= r; ++i) {
    kernel[i + r] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)));
    total += kernel[i + r];
  }
  for (float& k : kernel) k /= total;
  const int w = patch->width, h = patch->height;
  std::vector<float> rows(patch->occupancy.size(), 0.0f);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      for (int i = std::max(-r, -x); i <= std::min(r, w - 1 - x); ++i) {
        sum += kernel[i + r] * patch->at(x + i, y);
      }
      rows[static_cast<size_t>(y) * w + x] = sum;
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      for (int j = std::max(-r, -y); j <= std::min(r, h - 1 - y); ++j) {
        sum += kernel[j + r] * rows[static_cast<size_t>(y + j) * w + x];
      }
      patch->at(x, y) = sum;
    }
  }
}

struct Region {
  std::vector<grid::CellIndex> cells;
};

std::vector<Region> GrowRegions(Mask mask, int width, int height, int link) {
  std::vector<Region> regions;
  std::vector<grid::CellIndex> stack;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!mask[static_cast<size_t>(y) * width + x]) continue;
      Region region;
      mask[static_cast<size_t>(y) * width + x] = 0;
      stack.push_back({x, y});
      while (!stack.empty()) {
        const grid::CellIndex c = stack.back();
        stack.pop_back();
        region.cells.push_back(c);
        for (int dy = -link; dy <= link; ++dy) {
          for (int dx = -link; dx <= link; ++dx) {
            const int nx = c.x + dx, ny = c.y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            uint8_t& m = mask[static_cast<size_t>(ny) * width + nx];
            if (!m) continue;
            m = 0;
            stack.push_back({nx, ny});
          }
        }
      }
      regions.push_back(std::move(region));
    }
  }
  return regions;
}

// Fewer cells than this are never an object for being alone (a 3-cell blob is what a leg seen in
// one scan, or a speck of noise, leaves); they recur only when small_region_cells is set to 3.
constexpr int kMinLoneCells = 4;

// Whether a small region is compact: its bounding box at most 3 cells a side and at least half
// filled (a bin, a leg), not a strand along a scan line or a scatter of specks region growing
// linked.
bool Compact(const std::vector<grid::CellIndex>& cells) {
  int x0 = cells[0].x, x1 = x0, y0 = cells[0].y, y1 = y0;
  for (const grid::CellIndex& c : cells) {
    x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
    y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
  }
  const int w = x1 - x0 + 1, h = y1 - y0 + 1;
  return w <= 3 && h <= 3 && 2 * static_cast<int>(cells.size()) >= w * h;
}

// Whether a region is alone: no cell of `raw` (the map's difference cells before filtering)
// within `radius` cells of its bounding box, except within `own` cells of it (the region's own
// cells the filter trimmed).
bool Lone(const std::vector<grid::CellIndex>& cells, const Mask& raw, int width, int height,
          int own, int radius) {
  int x0 = cells[0].x, x1 = x0, y0 = cells[0].y, y1 = y0;
  for (const grid::CellIndex& c : cells) {
    x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
    y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
  }
  for (int y = std::max(0, y0 - radius); y <= std::min(height - 1, y1 + radius); ++y) {
    for (int x = std::max(0, x0 - radius); x <= std::min(width - 1, x1 + radius); ++x) {
      const bool near_own = x >= x0 - own && x <= x1 + own && y >= y0 - own && y <= y1 + own;
      if (!near_own && raw[static_cast<size_t>(y) * width + x]) return false;
    }
  }
  return true;
}

}  // namespace

std::string GeometryMismatch(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b) {
  if (a.width() != b.width() || a.height() != b.height()) {
    return "size " + std::to_string(a.width()) + " x " + std::to_string(a.height()) + " vs " +
           std::to_string(b.width()) + " x " + std::to_string(b.height()) + " cells";
  }
  if (std::abs(a.resolution() - b.resolution()) > 1e-9 * a.resolution()) {
    return "resolution " + Number(a.resolution()) + " vs " + Number(b.resolution()) + " m";
  }
  const Pose2& p = a.origin();
  const Pose2& q = b.origin();
  const double tolerance = 1e-3 * a.resolution();
  if (std::abs(p.x - q.x) > tolerance || std::abs(p.y - q.y) > tolerance ||
      std::abs(p.yaw - q.yaw) > 1e-6) {
    return "origin (" + Number(p.x) + ", " + Number(p.y) + ", " + Number(p.yaw) + ") vs (" +
           Number(q.x) + ", " + Number(q.y) + ", " + Number(q.yaw) + ")";
  }
  return "";
}

StatusOr<SnapshotSet> ExtractSnapshots(const std::vector<grid::OccupancyGrid>& maps,
                                       const SnapshotOptions& options, size_t first_map) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  if (maps.size() < 2 || first_map + 2 > maps.size()) {
    return InvalidArgumentError("object learning needs at least two maps of the same place, got " +
                                std::to_string(maps.size()));
  }
  for (size_t t = 1; t < maps.size(); ++t) {
    const std::string mismatch = GeometryMismatch(maps[0], maps[t]);
    if (!mismatch.empty()) {
      return InvalidArgumentError("map " + std::to_string(t) +
                                  " does not share map 0's frame: " + mismatch);
    }
  }
  const int width = maps[0].width();
  const int height = maps[0].height();
  if (width == 0 || height == 0) return InvalidArgumentError("map 0 is empty");
  const size_t cells = static_cast<size_t>(width) * height;

  // Only the maps in use hold masks (memory grows with the maps differenced).
  std::vector<Mask> occupied(maps.size());
  std::vector<Mask> clear(maps.size());  // free, nothing but free cells near
  for (size_t t = first_map; t < maps.size(); ++t) {
    occupied[t].assign(cells, 0);
    clear[t].assign(cells, 0);
    Mask free(cells, 0);
    for (size_t i = 0; i < cells; ++i) {
      const grid::CellState state = grid::StateOf(maps[t].data()[i], options.thresholds);
      occupied[t][i] = state == grid::CellState::kOccupied;
      free[i] = state == grid::CellState::kFree;
    }
    // A free cell next to an occupied or unknown one is not trusted: a ray grazing a wall clears
    // cells of its face, and a wall seen one cell further on is not a moved object.
    Mask not_free(cells, 0);
    for (size_t i = 0; i < cells; ++i) not_free[i] = !free[i];
    const Mask near = Dilate(not_free, width, height, options.guard_radius);
    for (size_t i = 0; i < cells; ++i) clear[t][i] = free[i] && !near[i];
  }

  struct Found {
    int map_index;
    Region region;
    grid::CellIndex centre;
    double radius;         // cells, farthest region cell from the centre cell
    bool small;            // below min_region_cells: kept only if it recurs in another map, or
    bool compact = false;  // and it is compact,
    bool lone = false;     // or compact, of kMinLoneCells or more, and alone (isolation_radius_m)
    bool drop = false;
  };
  std::vector<Found> found;
  SnapshotSet result;
  result.per_map.assign(maps.size(), 0);
  // The radius limit is metric: a row of desks is as long in metres at any resolution.
  const int max_radius_cells =
      std::max(1, static_cast<int>(std::floor(options.max_region_radius_m / maps[0].resolution())));
  const RegionLimits limits{options.max_region_cells, max_radius_cells};
  const int smallest =
      options.small_region_cells > 0 ? options.small_region_cells : options.min_region_cells;
  for (size_t t = first_map; t < maps.size(); ++t) {
    Mask diff(cells, 0);
    for (size_t i = 0; i < cells; ++i) {
      if (!occupied[t][i]) continue;
      for (size_t u = first_map; u < maps.size() && !diff[i]; ++u) {
        diff[i] = u != t && clear[u][i];
      }
    }
    const Mask raw = diff;  // before the filter: speckle counts against a small piece's isolation
    diff = LowPass(diff, width, height, options.filter_radius, options.filter_threshold);
    int split = 0, parts = 0;
    bool sliced = false;
    for (Region& grown : GrowRegions(std::move(diff), width, height, options.link_cells)) {
      std::vector<Region> regions;
      if (static_cast<int>(grown.cells.size()) > options.max_region_cells ||
          RegionRadius(grown.cells) > max_radius_cells) {
        SplitRegions pieces = SplitRegion(grown.cells, limits);
        ++split;
        parts += static_cast<int>(pieces.parts.size());
        sliced = sliced || pieces.sliced;
        for (std::vector<grid::CellIndex>& part : pieces.parts)
          regions.push_back({std::move(part)});
      } else {
        regions.push_back(std::move(grown));
      }
      for (Region& region : regions) {
        const int n = static_cast<int>(region.cells.size());
        if (n < smallest) continue;
        double sx = 0.0, sy = 0.0;
        for (const grid::CellIndex& c : region.cells) {
          sx += c.x;
          sy += c.y;
        }
        const grid::CellIndex centre{static_cast<int>(std::lround(sx / n)),
                                     static_cast<int>(std::lround(sy / n))};
        double radius = 0.0;
        for (const grid::CellIndex& c : region.cells) {
          radius = std::max(radius, std::hypot(c.x - centre.x, c.y - centre.y));
        }
        const bool small = n < options.min_region_cells;
        const bool compact = small && Compact(region.cells);
        const bool lone =
            compact && n >= kMinLoneCells && options.isolation_radius_m > 0.0 &&
            Lone(region.cells, raw, width, height, std::max(1, options.filter_radius),
                 static_cast<int>(std::ceil(options.isolation_radius_m / maps[0].resolution())));
        found.push_back(
            {static_cast<int>(t), std::move(region), centre, radius, small, compact, lone});
      }
    }
    if (split > 0) {
      result.warnings.push_back(
          "map " + std::to_string(t) + ": " + std::to_string(split) +
          " changed region(s) larger than max_region_cells (" +
          std::to_string(options.max_region_cells) + " cells) or max_region_radius_m (" +
          Number(options.max_region_radius_m) + " m) were split into " + std::to_string(parts) +
          " parts" +
          (sliced ? ", some cut into slices (touching objects with no neck between them)" : ""));
    }
  }
  // Small regions are kept when one of a similar size shows in another map (a small object that
  // moved recurs, a lone cluster of speckle does not) and they stand apart from every other
  // region of their map: a small piece next to a larger one is a fragment of that object's
  // outline (a chair's leg seen apart), which as a snapshot of its own would split the object.
  {
    struct Box {
      int x0, y0, x1, y1;
    };
    auto box_of = [](const Region& region) {
      Box b{region.cells[0].x, region.cells[0].y, region.cells[0].x, region.cells[0].y};
      for (const grid::CellIndex& c : region.cells) {
        b.x0 = std::min(b.x0, c.x), b.x1 = std::max(b.x1, c.x);
        b.y0 = std::min(b.y0, c.y), b.y1 = std::max(b.y1, c.y);
      }
      return b;
    };
    const int isolation = 2 * options.link_cells + 1;  // cells between bounding boxes
    auto isolated = [&](size_t i) {
      const Box a = box_of(found[i].region);
      for (size_t j = 0; j < found.size(); ++j) {
        if (j == i || found[j].map_index != found[i].map_index) continue;
        const Box b = box_of(found[j].region);
        const int gap = std::max({b.x0 - a.x1, a.x0 - b.x1, b.y0 - a.y1, a.y0 - b.y1});
        if (gap < isolation) return false;
      }
      return true;
    };
    std::vector<Found> kept;
    int recurring = 0, lone = 0;
    // Sorted extents of a region's bounding box: a moved object keeps them (up to a turn).
    auto extents = [](const Region& region) {
      int x0 = region.cells[0].x, x1 = x0, y0 = region.cells[0].y, y1 = y0;
      for (const grid::CellIndex& c : region.cells) {
        x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
        y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
      }
      return std::minmax(x1 - x0, y1 - y0);
    };
    for (size_t i = 0; i < found.size(); ++i) {
      if (!found[i].small) continue;
      const double n = static_cast<double>(found[i].region.cells.size());
      bool recurs = false;
      if (!isolated(i)) {
        found[i].drop = true;
        continue;
      }
      for (size_t j = 0; j < found.size() && !recurs; ++j) {
        if (found[j].map_index == found[i].map_index) continue;
        const double m = static_cast<double>(found[j].region.cells.size());
        const auto [a0, a1] = extents(found[i].region);
        const auto [b0, b1] = extents(found[j].region);
        recurs = m <= 1.5 * n && n <= 1.5 * m && std::abs(a0 - b0) <= 1 && std::abs(a1 - b1) <= 1;
      }
      found[i].drop = !found[i].compact || (!recurs && !found[i].lone);
      if (found[i].compact && recurs) ++recurring;
      if (!recurs && found[i].lone) ++lone;
    }
    for (Found& f : found) {
      if (!f.drop) kept.push_back(std::move(f));
    }
    found = std::move(kept);
    if (recurring > 0) {
      result.warnings.push_back(std::to_string(recurring) + " small region(s) of fewer than " +
                                std::to_string(options.min_region_cells) +
                                " cells were kept because regions of their size recur in other "
                                "maps (small_region_cells " +
                                std::to_string(options.small_region_cells) + ")");
    }
    if (lone > 0) {
      result.warnings.push_back(std::to_string(lone) + " small region(s) of fewer than " +
                                std::to_string(options.min_region_cells) +
                                " cells were kept because they are compact and nothing else "
                                "changed within " +
                                Number(options.isolation_radius_m) +
                                " m of them (isolation_radius_m)");
    }
  }
  for (const Found& f : found) ++result.per_map[f.map_index];

  // One size for all: a disc of the largest radius fits at any rotation, plus the margin.
  int side = options.patch_cells;
  if (side == 0) {
    double radius = 0.0;
    for (const Found& f : found) radius = std::max(radius, f.radius);
    side = 2 * (static_cast<int>(std::ceil(radius)) + options.margin_cells +
                static_cast<int>(std::ceil(2.0 * options.blur_cells))) +
           1;
  }
  const int half = side / 2;
  const double resolution = maps[0].resolution();
  for (const Found& f : found) {
    Snapshot snapshot;
    snapshot.map_index = f.map_index;
    snapshot.centre = maps[0].CellCenter(f.centre.x, f.centre.y);
    snapshot.cells = static_cast<int>(f.region.cells.size());
    snapshot.patch.width = side;
    snapshot.patch.height = side;
    snapshot.patch.resolution = resolution;
    snapshot.patch.occupancy.assign(static_cast<size_t>(side) * side, 0.0f);
    snapshot.patch.weight.assign(static_cast<size_t>(side) * side, 0.0f);
    const grid::OccupancyGrid& map = maps[f.map_index];
    // Observed: free in this map, or part of the object. Unknown cells (the object's far side,
    // its inside) and other obstacles (which may hide part of it) are missing data.
    for (int py = 0; py < side; ++py) {
      for (int px = 0; px < side; ++px) {
        const int x = f.centre.x + px - half, y = f.centre.y + py - half;
        if (!map.Contains(x, y)) continue;
        if (map.StateAt(x, y, options.thresholds) == grid::CellState::kFree) {
          snapshot.patch.weight[static_cast<size_t>(py) * side + px] = 1.0f;
        }
      }
    }
    for (const grid::CellIndex& c : f.region.cells) {
      const int px = c.x - f.centre.x + half;
      const int py = c.y - f.centre.y + half;
      if (px < 0 || py < 0 || px >= side || py >= side) continue;  // patch_cells set too small
      snapshot.patch.at(px, py) = std::clamp(map.at(c.x, c.y) / 100.0f, 0.0f, 1.0f);
      snapshot.patch.weight[static_cast<size_t>(py) * side + px] = 1.0f;
    }
    Blur(options.blur_cells, &snapshot.patch);
    result.snapshots.push_back(std::move(snapshot));
  }
  return result;
}

}  // namespace fleetmap::object_learning
