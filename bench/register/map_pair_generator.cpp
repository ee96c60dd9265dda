#include "bench/register/map_pair_generator.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace fleetmap::bench {
namespace {

// Cells as one index y * width + x.
using Mask = std::vector<uint8_t>;

// Free cells in breadth-first (geodesic, 8-connected) order from `start`, at most `limit`.
std::vector<int> GeodesicOrder(const grid::OccupancyGrid& map, const Mask& free, int start,
                               size_t limit) {
  const int w = map.width(), h = map.height();
  std::vector<int> order;
  Mask seen(free.size(), 0);
  std::deque<int> queue{start};
  seen[start] = 1;
  while (!queue.empty() && order.size() < limit) {
    const int i = queue.front();
    queue.pop_front();
    order.push_back(i);
    const int x = i % w, y = i / w;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const int n = ny * w + nx;
        if (!seen[n] && free[n]) {
          seen[n] = 1;
          queue.push_back(n);
        }
      }
    }
  }
  return order;
}

// What a robot that drove over the first `count` cells of `order` has seen: the known cells
// within `sight` cells of them, with a ragged border (moved in and out by a smooth random field).
Mask ExploredRegion(const grid::OccupancyGrid& map, const Mask& known,
                    const std::vector<int>& order, size_t count, const MapPairOptions& options,
                    std::mt19937& rng) {
  const int w = map.width(), h = map.height();
  constexpr int kSight = 3;
  // Work in the window around the driven cells that the sight and the frontier can reach.
  const int reach = kSight + static_cast<int>(std::ceil(options.frontier_amplitude_cells)) + 2;
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (size_t k = 0; k < count && k < order.size(); ++k) {
    x0 = std::min(x0, order[k] % w);
    x1 = std::max(x1, order[k] % w);
    y0 = std::min(y0, order[k] / w);
    y1 = std::max(y1, order[k] / w);
  }
  Mask region(known.size(), 0);
  if (x1 < 0) return region;
  x0 = std::max(0, x0 - reach);
  y0 = std::max(0, y0 - reach);
  x1 = std::min(w - 1, x1 + reach);
  y1 = std::min(h - 1, y1 + reach);
  const int ww = x1 - x0 + 1, wh = y1 - y0 + 1;
  // A one-pixel unseen border, so distances inside measure to the window's edge too.
  cv::Mat driven(wh + 2, ww + 2, CV_8U, cv::Scalar(0));
  for (size_t k = 0; k < count && k < order.size(); ++k) {
    driven.at<uint8_t>(order[k] / w - y0 + 1, order[k] % w - x0 + 1) = 255;
  }
  cv::Mat seen;
  cv::dilate(driven, seen,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * kSight + 1, 2 * kSight + 1}));
  for (int y = 0; y < wh + 2; ++y) {
    for (int x = 0; x < ww + 2; ++x) {
      const int sx = x + x0 - 1, sy = y + y0 - 1;
      if (sx < 0 || sy < 0 || sx >= w || sy >= h || !known[sy * w + sx]) {
        seen.at<uint8_t>(y, x) = 0;
      }
    }
  }
  // Smooth noise in [-amplitude, amplitude]: random values on a coarse lattice, interpolated.
  const double wavelength = std::max(2.0, options.frontier_wavelength_cells);
  const int lw = static_cast<int>(std::ceil((ww + 2) / wavelength)) + 2;
  const int lh = static_cast<int>(std::ceil((wh + 2) / wavelength)) + 2;
  cv::Mat lattice(lh, lw, CV_32F);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int y = 0; y < lh; ++y) {
    for (int x = 0; x < lw; ++x) lattice.at<float>(y, x) = unit(rng);
  }
  cv::Mat noise;
  cv::resize(lattice, noise, {static_cast<int>(lw * wavelength), static_cast<int>(lh * wavelength)},
             0, 0, cv::INTER_CUBIC);
  cv::Mat inside, outside, not_seen;
  cv::distanceTransform(seen, inside, cv::DIST_L2, 3);
  cv::bitwise_not(seen, not_seen);
  cv::distanceTransform(not_seen, outside, cv::DIST_L2, 3);
  const float amplitude = static_cast<float>(options.frontier_amplitude_cells);
  for (int y = 1; y <= wh; ++y) {
    for (int x = 1; x <= ww; ++x) {
      const float n = amplitude * noise.at<float>(y, x);
      const int i = (y + y0 - 1) * w + (x + x0 - 1);
      region[i] = seen.at<uint8_t>(y, x) ? inside.at<float>(y, x) > n
                                         : known[i] && outside.at<float>(y, x) <= -n;
    }
  }
  return region;
}

struct Box {
  int x0, y0, x1, y1;
};

Box BoundingBox(const Mask& region, int w, int h) {
  Box box{w, h, -1, -1};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!region[y * w + x]) continue;
      box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x), std::max(box.y1, y)};
    }
  }
  return box;
}

// MapPairOptions::wall_noise on `map`: moves decided on the map as it was, so one move does not
// make another face.
void MoveWallFaces(grid::OccupancyGrid* map, double probability, std::mt19937& rng) {
  const grid::OccupancyGrid before = *map;
  const auto state = [&before](int x, int y) {
    return before.Contains(x, y) ? before.StateAt(x, y) : grid::CellState::kUnknown;
  };
  std::bernoulli_distribution move(probability), advance(0.5);
  constexpr int kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (int y = 0; y < before.height(); ++y) {
    for (int x = 0; x < before.width(); ++x) {
      if (state(x, y) != grid::CellState::kOccupied) continue;
      for (const auto& [dx, dy] : kSteps) {
        if (state(x + dx, y + dy) != grid::CellState::kFree || !move(rng)) continue;
        if (advance(rng)) {
          map->at(x + dx, y + dy) = grid::kOccupiedValue;
        } else if (state(x - dx, y - dy) == grid::CellState::kOccupied) {
          map->at(x, y) = grid::kFreeValue;
        }
        break;  // one move per face cell
      }
    }
  }
}

// The region's cells of `map` (unknown elsewhere) cropped to its bounding box plus a margin, with
// a few specks (isolated cells of the wrong state) and, with MapPairOptions::wall_noise, wall
// faces moved.
grid::OccupancyGrid RegionMap(const grid::OccupancyGrid& map, const Mask& region,
                              const MapPairOptions& options, std::mt19937& rng) {
  const int w = map.width(), h = map.height();
  constexpr int kMargin = 2;
  const Box box = BoundingBox(region, w, h);
  grid::OccupancyGrid out =
      CropCells(map, box.x0 - kMargin, box.y0 - kMargin, box.x1 - box.x0 + 1 + 2 * kMargin,
                box.y1 - box.y0 + 1 + 2 * kMargin);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      const int sx = x + box.x0 - kMargin, sy = y + box.y0 - kMargin;
      if (!map.Contains(sx, sy) || !region[sy * w + sx]) out.at(x, y) = grid::kUnknownValue;
    }
  }
  std::uniform_int_distribution<int> specks(options.min_specks,
                                            std::max(options.min_specks, options.max_specks));
  std::uniform_int_distribution<int> px(0, out.width() - 1), py(0, out.height() - 1);
  std::bernoulli_distribution occupied(0.5);
  for (int k = specks(rng); k > 0; --k) {
    const int x = px(rng), y = py(rng);
    const grid::CellState state = out.StateAt(x, y);
    if (state == grid::CellState::kUnknown) {
      out.at(x, y) = occupied(rng) ? grid::kOccupiedValue : grid::kFreeValue;
    } else {
      out.at(x, y) = state == grid::CellState::kFree ? grid::kOccupiedValue : grid::kFreeValue;
    }
  }
  if (options.wall_noise > 0.0) MoveWallFaces(&out, options.wall_noise, rng);
  return out;
}

// B's cells whose source cell (where the truth lays them) lies in `region`; the rest unknown.
grid::OccupancyGrid SeenPart(const MapPair& pair, const grid::OccupancyGrid& source,
                             const Mask& region) {
  grid::OccupancyGrid part = pair.b;
  for (int y = 0; y < part.height(); ++y) {
    for (int x = 0; x < part.width(); ++x) {
      const std::optional<grid::CellIndex> cell =
          source.CellAt(pair.a_from_b * part.CellCenter(x, y));
      if (!cell || !region[static_cast<size_t>(cell->y) * source.width() + cell->x]) {
        part.at(x, y) = grid::kUnknownValue;
      }
    }
  }
  return part;
}

double Overlap(const Mask& a, const Mask& b) {
  size_t in_b = 0, shared = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    in_b += b[i];
    shared += b[i] && a[i];
  }
  return in_b > 0 ? static_cast<double>(shared) / in_b : 0.0;
}

}  // namespace

grid::OccupancyGrid CropCells(const grid::OccupancyGrid& map, int x0, int y0, int w, int h) {
  Transform2 corner = Transform2::Identity();
  corner.translate(Point2(x0 * map.resolution(), y0 * map.resolution()));
  grid::OccupancyGrid out(w, h, map.resolution(),
                          Pose2::FromTransform(map.origin().ToTransform() * corner));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (map.Contains(x0 + x, y0 + y)) out.at(x, y) = map.at(x0 + x, y0 + y);
    }
  }
  return out;
}

grid::OccupancyGrid TurnIntoNewFrame(const grid::OccupancyGrid& map, double yaw,
                                     const Pose2& origin, Transform2* map_from_turned) {
  const double res = map.resolution();
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double w = map.width() * res, h = map.height() * res;
  const int width = static_cast<int>(std::ceil((std::abs(c) * w + std::abs(s) * h) / res)) + 2;
  const int height = static_cast<int>(std::ceil((std::abs(s) * w + std::abs(c) * h) / res)) + 2;
  // grid_new = R (grid_old - centre_old) + centre_new, both grids' corners at their origin.
  Transform2 new_from_old = Transform2::Identity();
  new_from_old.translate(Point2(width * res / 2, height * res / 2));
  new_from_old.rotate(yaw);
  new_from_old.translate(Point2(-w / 2, -h / 2));
  const Transform2 old_from_new = new_from_old.inverse();
  grid::OccupancyGrid out(width, height, res, origin);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Point2 p = old_from_new * Point2((x + 0.5) * res, (y + 0.5) * res);
      const int cx = static_cast<int>(std::floor(p.x() / res));
      const int cy = static_cast<int>(std::floor(p.y() / res));
      if (map.Contains(cx, cy)) out.at(x, y) = map.at(cx, cy);
    }
  }
  *map_from_turned = map.origin().ToTransform() * old_from_new * origin.ToTransform().inverse();
  return out;
}

grid::OccupancyGrid Warp(const grid::OccupancyGrid& map, const Point2& pivot, double scale,
                         double bend_per_metre) {
  const double res = map.resolution();
  const Transform2 map_from_grid = map.origin().ToTransform();
  const Point2 pivot_grid = map_from_grid.inverse() * pivot;
  // Margin enough for the scale and the bend at the grid's far corner.
  const double reach = std::hypot(map.width(), map.height());
  const double turn = std::abs(bend_per_metre) * reach * res;
  const int margin = static_cast<int>(std::ceil(reach * (std::abs(scale) + turn))) + 2;
  Transform2 corner = Transform2::Identity();
  corner.translate(Point2(-margin * res, -margin * res));
  grid::OccupancyGrid out(map.width() + 2 * margin, map.height() + 2 * margin, res,
                          Pose2::FromTransform(map_from_grid * corner));
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      // Invert w = pivot + (1 + scale) R(bend * d.x) d by a fixed point on d (the turn is small).
      const Point2 e =
          (Point2((x - margin + 0.5) * res, (y - margin + 0.5) * res) - pivot_grid) / (1.0 + scale);
      Point2 d = e;
      for (int k = 0; k < 4; ++k) d = Eigen::Rotation2Dd(-bend_per_metre * d.x()) * e;
      const Point2 p = pivot_grid + d;
      const int cx = static_cast<int>(std::floor(p.x() / res));
      const int cy = static_cast<int>(std::floor(p.y() / res));
      if (map.Contains(cx, cy)) out.at(x, y) = map.at(cx, cy);
    }
  }
  return out;
}

WarpedPoint WarpPoint(const grid::OccupancyGrid& map, const Point2& pivot, double scale,
                      double bend_per_metre, const Point2& p) {
  const Transform2 map_from_grid = map.origin().ToTransform();
  const Point2 pivot_grid = map_from_grid.inverse() * pivot;
  const Point2 d = map_from_grid.inverse() * p - pivot_grid;
  const double turn = bend_per_metre * d.x();
  const Point2 w = pivot_grid + (1.0 + scale) * (Eigen::Rotation2Dd(turn) * d);
  return {map_from_grid * w, turn};
}

Point2 OverlapCentroid(const MapPair& pair) {
  const Transform2 map_from_grid_b = pair.b.origin().ToTransform();
  const Transform2 grid_a_from_b = pair.a.origin().ToTransform().inverse() * pair.a_from_b;
  const double res_b = pair.b.resolution(), res_a = pair.a.resolution();
  Point2 sum(0.0, 0.0);
  int64_t count = 0;
  for (int y = 0; y < pair.b.height(); ++y) {
    for (int x = 0; x < pair.b.width(); ++x) {
      if (pair.b.at(x, y) == grid::kUnknownValue) continue;
      const Point2 p = map_from_grid_b * Point2((x + 0.5) * res_b, (y + 0.5) * res_b);
      const Point2 q = grid_a_from_b * p;
      const int ax = static_cast<int>(std::floor(q.x() / res_a));
      const int ay = static_cast<int>(std::floor(q.y() / res_a));
      if (!pair.a.Contains(ax, ay) || pair.a.at(ax, ay) == grid::kUnknownValue) continue;
      sum += p;
      ++count;
    }
  }
  return count > 0 ? Point2(sum / static_cast<double>(count)) : KnownCentroid(pair.b);
}

Point2 KnownCentroid(const grid::OccupancyGrid& map) {
  Point2 sum(0, 0);
  int n = 0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      if (map.StateAt(x, y) == grid::CellState::kUnknown) continue;
      sum += map.CellCenter(x, y);
      ++n;
    }
  }
  return n > 0 ? Point2(sum / n) : Point2(0, 0);
}

StatusOr<MapPair> MakeMapPair(const grid::OccupancyGrid& source, double target_overlap,
                              const MapPairOptions& options, std::mt19937& rng) {
  if (!(target_overlap > 0.0 && target_overlap < 1.0)) {
    return InvalidArgumentError("pair overlap must be in (0, 1)");
  }
  const int w = source.width(), h = source.height();
  Mask known(source.cell_count(), 0), free(source.cell_count(), 0);
  std::vector<int> free_cells;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const grid::CellState state = source.StateAt(x, y);
      known[y * w + x] = state != grid::CellState::kUnknown;
      free[y * w + x] = state == grid::CellState::kFree;
      if (state == grid::CellState::kFree) free_cells.push_back(y * w + x);
    }
  }
  if (free_cells.size() < 1000) {
    return InvalidArgumentError("map has " + std::to_string(free_cells.size()) +
                                " free cells: too few to crop robot maps from");
  }
  std::uniform_int_distribution<size_t> pick(0, free_cells.size() - 1);
  std::uniform_real_distribution<double> share(options.min_crop_share, options.max_crop_share);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int attempts = 0;
  while (attempts < options.max_attempts) {
    // A: a start in the main free space (one that reaches at least half of the free cells).
    const std::vector<int> from_a = GeodesicOrder(source, free, free_cells[pick(rng)], SIZE_MAX);
    ++attempts;
    if (from_a.size() < free_cells.size() / 2) continue;
    const Mask region_a = ExploredRegion(
        source, known, from_a, static_cast<size_t>(share(rng) * from_a.size()), options, rng);
    // B: a start at a geodesic distance from A's (a quantile of from_a), bisected on the overlap
    // (it falls as B's start moves away).
    double lo = 0.0, hi = 1.0;
    for (int step = 0; step < 10 && attempts < options.max_attempts; ++step, ++attempts) {
      const double q = std::clamp(lo + (hi - lo) * (0.35 + 0.3 * unit(rng)), 0.0, 1.0);
      const int start_b = from_a[static_cast<size_t>(q * (from_a.size() - 1))];
      const std::vector<int> from_b =
          GeodesicOrder(source, free, start_b, static_cast<size_t>(share(rng) * from_a.size()));
      const Mask region_b = ExploredRegion(source, known, from_b, from_b.size(), options, rng);
      const double overlap = Overlap(region_a, region_b);
      if (std::abs(overlap - target_overlap) <= options.overlap_tolerance) {
        MapPair pair;
        pair.overlap = overlap;
        pair.a = RegionMap(source, region_a, options, rng);
        const grid::OccupancyGrid b_in_source = RegionMap(source, region_b, options, rng);
        std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
        std::uniform_real_distribution<double> offset(-options.max_origin_offset,
                                                      options.max_origin_offset);
        pair.yaw_b = angle(rng);
        const Pose2 origin{source.origin().x + offset(rng), source.origin().y + offset(rng),
                           angle(rng)};
        pair.b = TurnIntoNewFrame(b_in_source, pair.yaw_b, origin, &pair.a_from_b);
        for (int k = 1; k < options.growth_steps; ++k) {
          const size_t driven = from_b.size() * static_cast<size_t>(k) / options.growth_steps;
          pair.b_growing.push_back(
              SeenPart(pair, source, ExploredRegion(source, known, from_b, driven, options, rng)));
        }
        return pair;
      }
      (overlap > target_overlap ? lo : hi) = q;
    }
  }
  return NotFoundError("no pair within " + std::to_string(options.overlap_tolerance) +
                       " of overlap " + std::to_string(target_overlap) + " in " +
                       std::to_string(options.max_attempts) + " attempts");
}

}  // namespace fleetmap::bench
