#include "bench/objects/real_plan_series.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "common/grid/map_io.hpp"

namespace fleetmap::bench {
namespace {

using Mask = std::vector<uint8_t>;

struct ShapeSize {
  double length;  // metres along the piece's x axis
  double width;   // along its y axis
};

ShapeSize SizeOf(PlanShape shape) {
  switch (shape) {
    case PlanShape::kDesk:
      return {1.2, 0.6};
    case PlanShape::kCabinet:
      return {0.8, 0.4};
    case PlanShape::kTable:
      return {0.8, 0.8};
    case PlanShape::kLShape:
      return {1.0, 0.8};
    case PlanShape::kBin:
      return {0.4, 0.4};
    case PlanShape::kSmallBin:
      return {0.2, 0.2};
  }
  return {0.0, 0.0};
}

// Whether the piece-frame point (x, y) (metres, origin at the bounding box's centre) is inside.
bool Inside(PlanShape shape, double x, double y) {
  const ShapeSize s = SizeOf(shape);
  // A hair over half the size, so that a size of whole cells draws whole cells on both sides.
  const double hx = 0.5 * s.length + 1e-6, hy = 0.5 * s.width + 1e-6;
  switch (shape) {
    case PlanShape::kBin:
    case PlanShape::kSmallBin:
      return x * x + y * y <= hx * hx;
    case PlanShape::kLShape: {
      constexpr double kArm = 0.35;  // arm thickness, metres
      if (std::abs(x) > hx || std::abs(y) > hy) return false;
      return x <= -hx + kArm || y <= -hy + kArm;
    }
    default:
      return std::abs(x) <= hx && std::abs(y) <= hy;
  }
}

// The cells of `shape` standing at cell (cx, cy) turned by `yaw`.
std::vector<grid::CellIndex> Footprint(PlanShape shape, int cx, int cy, double yaw,
                                       double resolution) {
  const ShapeSize s = SizeOf(shape);
  const int r = static_cast<int>(std::ceil(0.5 * std::hypot(s.length, s.width) / resolution)) + 1;
  const double c = std::cos(yaw), sn = std::sin(yaw);
  std::vector<grid::CellIndex> cells;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const double wx = dx * resolution, wy = dy * resolution;
      // Into the piece frame: R(-yaw).
      const double px = c * wx + sn * wy, py = -sn * wx + c * wy;
      if (Inside(shape, px, py)) cells.push_back({cx + dx, cy + dy});
    }
  }
  return cells;
}

// Marks every cell within `r` cells (Chebyshev) of `cells` in `mask`.
void MarkAround(const std::vector<grid::CellIndex>& cells, int r, int width, int height,
                Mask* mask) {
  for (const grid::CellIndex& cell : cells) {
    for (int y = std::max(0, cell.y - r); y <= std::min(height - 1, cell.y + r); ++y) {
      for (int x = std::max(0, cell.x - r); x <= std::min(width - 1, cell.x + r); ++x) {
        (*mask)[static_cast<size_t>(y) * width + x] = 1;
      }
    }
  }
}

// The window of options' size with the most free cells (stride 8 cells), padded with unknown
// where the floor is smaller.
grid::OccupancyGrid CropToMostFree(const grid::OccupancyGrid& floor, int width, int height) {
  const int fw = floor.width(), fh = floor.height();
  std::vector<int64_t> sat(static_cast<size_t>(fw + 1) * (fh + 1), 0);
  auto s = [&](int x, int y) -> int64_t& { return sat[static_cast<size_t>(y) * (fw + 1) + x]; };
  for (int y = 0; y < fh; ++y) {
    for (int x = 0; x < fw; ++x) {
      s(x + 1, y + 1) =
          (floor.StateAt(x, y) == grid::CellState::kFree) + s(x, y + 1) + s(x + 1, y) - s(x, y);
    }
  }
  auto free_in = [&](int x0, int y0) {
    const int ax = std::clamp(x0, 0, fw), bx = std::clamp(x0 + width, 0, fw);
    const int ay = std::clamp(y0, 0, fh), by = std::clamp(y0 + height, 0, fh);
    return s(bx, by) - s(ax, by) - s(bx, ay) + s(ax, ay);
  };
  int best_x = std::min(0, (fw - width) / 2), best_y = std::min(0, (fh - height) / 2);
  int64_t best = -1;
  constexpr int kStride = 8;
  for (int y0 = std::min(0, fh - height); y0 <= std::max(0, fh - height); y0 += kStride) {
    for (int x0 = std::min(0, fw - width); x0 <= std::max(0, fw - width); x0 += kStride) {
      const int64_t f = free_in(x0, y0);
      if (f > best) best = f, best_x = x0, best_y = y0;
    }
  }
  const Pose2& o = floor.origin();
  const double r = floor.resolution();
  const Point2 shift = Eigen::Rotation2Dd(o.yaw) * Point2(best_x * r, best_y * r);
  grid::OccupancyGrid out(width, height, r, Pose2{o.x + shift.x(), o.y + shift.y(), o.yaw});
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (floor.Contains(x + best_x, y + best_y)) out.at(x, y) = floor.at(x + best_x, y + best_y);
    }
  }
  return out;
}

}  // namespace

const char* PlanShapeName(PlanShape shape) {
  switch (shape) {
    case PlanShape::kDesk:
      return "desk";
    case PlanShape::kCabinet:
      return "cabinet";
    case PlanShape::kTable:
      return "table";
    case PlanShape::kLShape:
      return "l_shape";
    case PlanShape::kBin:
      return "bin";
    case PlanShape::kSmallBin:
      return "small_bin";
  }
  return "?";
}

StatusOr<RealPlanSeries> MakeRealPlanSeries(const std::string& floor_yaml,
                                            const RealPlanOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(grid::LoadedMap loaded, grid::LoadMap(floor_yaml));
  StatusOr<RealPlanSeries> series = MakeRealPlanSeries(loaded.grid, options);
  if (!series.ok()) return InvalidArgumentError(floor_yaml + ": " + series.status().message());
  series->floor = floor_yaml;
  return series;
}

StatusOr<RealPlanSeries> MakeRealPlanSeries(const grid::OccupancyGrid& floor,
                                            const RealPlanOptions& options) {
  if (options.width < 16 || options.height < 16) {
    return InvalidArgumentError("real-plan maps must be at least 16 x 16 cells");
  }
  if (options.maps < 2) return InvalidArgumentError("a real-plan series needs at least 2 maps");
  if (options.pieces < 1) return InvalidArgumentError("a real-plan series needs at least 1 piece");
  if (!(options.gap >= 0.0)) return InvalidArgumentError("the gap around pieces must be >= 0");
  if (options.rows < 0) return InvalidArgumentError("rows of desks must be >= 0");
  if (floor.empty()) return InvalidArgumentError("the floor map is empty");
  const grid::OccupancyGrid base = CropToMostFree(floor, options.width, options.height);
  const int w = base.width(), h = base.height();
  const size_t cells = static_cast<size_t>(w) * h;
  const double res = base.resolution();
  const int gap = static_cast<int>(std::ceil(options.gap / res));

  // Floor cells with free floor all around them, `gap` cells wide.
  Mask blocked(cells, 0);
  std::vector<grid::CellIndex> walls;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (base.StateAt(x, y) != grid::CellState::kFree) walls.push_back({x, y});
    }
  }
  MarkAround(walls, gap, w, h, &blocked);
  std::vector<grid::CellIndex> clear;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!blocked[static_cast<size_t>(y) * w + x]) clear.push_back({x, y});
    }
  }

  RealPlanSeries series;
  if (clear.empty()) return InvalidArgumentError("no free floor to draw pieces on");
  std::mt19937_64 random(options.seed);
  std::uniform_int_distribution<size_t> pick(0, clear.size() - 1);
  std::uniform_int_distribution<int> quarter(0, 3);
  // How many earlier maps had a piece on each cell (with the gap). A piece is drawn where no
  // earlier one stood if the floor allows, else where at most maps - 2 earlier ones stood: every
  // cell of every piece is then free in at least one other map, so it is a difference (a piece
  // standing where pieces stand in all other maps cannot be found by differencing at all).
  std::vector<uint8_t> earlier(cells, 0);
  const int most_earlier = options.maps - 2;
  // Placement groups: rows of desks (kRowLength desks end to end, one free cell between them,
  // as desks in an office stand) first, then single pieces of the other shapes in turn.
  constexpr int kRowLength = 4;
  std::vector<std::vector<int>> groups;
  std::vector<PlanShape> shape_of(options.pieces);
  {
    const int in_rows = std::min(options.pieces, options.rows * kRowLength);
    for (int i = 0; i < options.pieces; ++i) {
      if (i < in_rows) {
        shape_of[i] = PlanShape::kDesk;
        if (i % kRowLength == 0) groups.emplace_back();
      } else {
        shape_of[i] = static_cast<PlanShape>((i - in_rows) % kPlanShapeCount);
        groups.emplace_back();
      }
      groups.back().push_back(i);
    }
  }
  // Desk to desk in a row, cells: a desk's drawn length and one free cell.
  int pitch = 0;
  {
    int lo = 0, hi = 0;
    for (const grid::CellIndex& c : Footprint(PlanShape::kDesk, 0, 0, 0.0, res)) {
      lo = std::min(lo, c.x);
      hi = std::max(hi, c.x);
    }
    pitch = hi - lo + 2;
  }
  constexpr int kTries = 3000;
  for (int t = 0; t < options.maps; ++t) {
    grid::OccupancyGrid map = base;
    Mask here = blocked;  // walls and this map's pieces, with the gap
    std::vector<PlacedPiece> placed;
    std::vector<std::vector<grid::CellIndex>> footprints;
    for (const std::vector<int>& group : groups) {
      std::vector<std::vector<grid::CellIndex>> cells_of;  // per piece of the group
      std::vector<double> yaws;
      bool over_earlier = false;
      for (int attempt = 0; attempt < 2 * kTries && cells_of.empty(); ++attempt) {
        const bool strict = attempt < kTries;  // first away from earlier maps' pieces
        const grid::CellIndex at = clear[pick(random)];
        const double yaw = 0.5 * std::numbers::pi * quarter(random);
        std::vector<std::vector<grid::CellIndex>> candidate;
        bool fits = true;
        bool touches_earlier = false;
        bool too_covered = false;
        for (size_t k = 0; k < group.size() && fits; ++k) {
          const double along = (k - 0.5 * (group.size() - 1.0)) * pitch;  // cells
          const int cx = at.x + static_cast<int>(std::lround(along * std::cos(yaw)));
          const int cy = at.y + static_cast<int>(std::lround(along * std::sin(yaw)));
          candidate.push_back(Footprint(shape_of[group[k]], cx, cy, yaw, res));
          for (const grid::CellIndex& c : candidate.back()) {
            if (!base.Contains(c.x, c.y) || here[static_cast<size_t>(c.y) * w + c.x]) {
              fits = false;
              break;
            }
            const int covered = earlier[static_cast<size_t>(c.y) * w + c.x];
            touches_earlier = touches_earlier || covered > 0;
            too_covered = too_covered || covered > most_earlier;
          }
        }
        if (!fits || too_covered || (strict && touches_earlier)) continue;
        cells_of = std::move(candidate);
        yaws.assign(group.size(), yaw);
        over_earlier = touches_earlier;
      }
      if (cells_of.empty()) {
        series.unplaced += static_cast<int>(group.size());
        continue;
      }
      if (over_earlier) series.overlapping_earlier += static_cast<int>(group.size());
      for (size_t k = 0; k < group.size(); ++k) {
        double sx = 0.0, sy = 0.0;
        for (const grid::CellIndex& c : cells_of[k]) {
          map.at(c.x, c.y) = 100;
          sx += c.x;
          sy += c.y;
        }
        const double n = static_cast<double>(cells_of[k].size());
        PlacedPiece piece;
        piece.piece = group[k];
        piece.shape = shape_of[group[k]];
        piece.yaw = yaws[k];
        piece.centre =
            base.origin().ToTransform() * Point2((sx / n + 0.5) * res, (sy / n + 0.5) * res);
        piece.cells = static_cast<int>(cells_of[k].size());
        placed.push_back(piece);
      }
      for (std::vector<grid::CellIndex>& f : cells_of) {
        MarkAround(f, gap, w, h, &here);
        footprints.push_back(std::move(f));
      }
    }
    Mask mine(cells, 0);
    for (const std::vector<grid::CellIndex>& f : footprints) MarkAround(f, gap, w, h, &mine);
    for (size_t i = 0; i < cells; ++i) earlier[i] += mine[i];
    series.maps.push_back(std::move(map));
    series.pieces.push_back(std::move(placed));
  }
  return series;
}

}  // namespace fleetmap::bench
