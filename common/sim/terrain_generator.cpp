#include "common/sim/terrain_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/core/number_format.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::sim {
namespace {

constexpr double kPi = std::numbers::pi;

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

// Adds the axis-aligned wall from `lo` to `hi` along x (horizontal) or y at coordinate `fixed`,
// leaving `gaps` (inside [lo, hi], disjoint) open; each gap becomes an open Door.
void AddAxisWall(bool horizontal, double fixed, double lo, double hi, std::vector<Interval> gaps,
                 double thickness, Terrain* terrain) {
  std::sort(gaps.begin(), gaps.end(),
            [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
  auto point = [&](double along) {
    return horizontal ? Point2(along, fixed) : Point2(fixed, along);
  };
  double cursor = lo;
  for (const Interval& gap : gaps) {
    if (gap.lo > cursor + 1e-9) {
      terrain->walls.push_back({point(cursor), point(gap.lo), thickness, ObstacleKind::kWall});
    }
    terrain->doors.push_back({point(gap.lo), point(gap.hi), true, thickness});
    cursor = gap.hi;
  }
  if (hi > cursor + 1e-9) {
    terrain->walls.push_back({point(cursor), point(hi), thickness, ObstacleKind::kWall});
  }
}

}  // namespace

void AddBoundary(double size, double thickness, Terrain* terrain) {
  // Each side runs the full edge, so the corner cells are covered too.
  const double b = thickness / 2.0;
  const Point2 ends[4][2] = {{{0.0, b}, {size, b}},
                             {{size - b, 0.0}, {size - b, size}},
                             {{size, size - b}, {0.0, size - b}},
                             {{b, size}, {b, 0.0}}};
  for (const auto& [a, c] : ends) {
    terrain->walls.push_back({a, c, thickness, ObstacleKind::kBoundary});
  }
}

namespace {

// ---- maze -------------------------------------------------------------------------------------

void GenerateMaze(const TerrainOptions& options, Random* random, Terrain* terrain) {
  const double size = options.size;
  const int n = std::max(2, static_cast<int>(std::lround(size / (2.0 + size / 40.0))));
  const double cell = size / n;
  // open_h[j * n + i]: the wall on line y = j * cell (1 <= j < n) above cell (i, j - 1) is removed.
  std::vector<bool> open_h(static_cast<size_t>(n) * (n + 1), false);
  std::vector<bool> open_v(static_cast<size_t>(n) * (n + 1), false);  // [i * n + j], x = i * cell
  std::vector<bool> visited(static_cast<size_t>(n) * n, false);
  std::vector<std::pair<int, int>> stack = {{0, 0}};
  visited[0] = true;
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    std::pair<int, int> options_left[4];
    int count = 0;
    const int dx[4] = {1, -1, 0, 0};
    const int dy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int nx = x + dx[k];
      const int ny = y + dy[k];
      if (nx < 0 || ny < 0 || nx >= n || ny >= n || visited[static_cast<size_t>(ny) * n + nx]) {
        continue;
      }
      options_left[count++] = {nx, ny};
    }
    if (count == 0) {
      stack.pop_back();
      continue;
    }
    const auto [nx, ny] = options_left[random->UniformInt(0, count - 1)];
    if (nx != x) {
      open_v[static_cast<size_t>(std::max(x, nx)) * n + y] = true;
    } else {
      open_h[static_cast<size_t>(std::max(y, ny)) * n + x] = true;
    }
    visited[static_cast<size_t>(ny) * n + nx] = true;
    stack.push_back({nx, ny});
  }
  // Braid: a few loops, as in real buildings and in the paper's maze terrains.
  for (int line = 1; line < n; ++line) {
    for (int k = 0; k < n; ++k) {
      if (!open_h[static_cast<size_t>(line) * n + k] && random->Bernoulli(0.1)) {
        open_h[static_cast<size_t>(line) * n + k] = true;
      }
      if (!open_v[static_cast<size_t>(line) * n + k] && random->Bernoulli(0.1)) {
        open_v[static_cast<size_t>(line) * n + k] = true;
      }
    }
  }
  // One segment per run of consecutive closed edges on a line.
  const double t = options.wall_thickness;
  for (int line = 1; line < n; ++line) {
    for (int pass = 0; pass < 2; ++pass) {
      const bool horizontal = pass == 0;
      const std::vector<bool>& open = horizontal ? open_h : open_v;
      int k = 0;
      while (k < n) {
        if (open[static_cast<size_t>(line) * n + k]) {
          ++k;
          continue;
        }
        int end = k;
        while (end < n && !open[static_cast<size_t>(line) * n + end]) ++end;
        const double fixed = line * cell;
        const Point2 a = horizontal ? Point2(k * cell, fixed) : Point2(fixed, k * cell);
        const Point2 b = horizontal ? Point2(end * cell, fixed) : Point2(fixed, end * cell);
        terrain->walls.push_back({a, b, t, ObstacleKind::kWall});
        k = end;
      }
    }
  }
  terrain->start = {cell / 2.0, cell / 2.0, 0.0};
}

// ---- office -----------------------------------------------------------------------------------

struct Room {
  double x_lo, x_hi, y_lo, y_hi;
  Point2 door;  // centre of its corridor door
};

void AddFurniture(const Room& room, const std::vector<Point2>& keep_clear, double wall_thickness,
                  Random* random, Terrain* terrain) {
  const double margin = wall_thickness / 2.0 + 0.2;
  const double area = (room.x_hi - room.x_lo) * (room.y_hi - room.y_lo);
  const int items = random->UniformInt(0, 2) + (area > 20.0 ? 1 : 0);
  std::vector<std::pair<Point2, double>> placed;  // centre, half diagonal
  for (int item = 0; item < items; ++item) {
    for (int attempt = 0; attempt < 12; ++attempt) {
      const double w = random->Uniform(0.5, 1.6);
      const double h = random->Uniform(0.4, 1.0);
      const double angle = random->Bernoulli(0.25) ? random->Uniform(0.0, kPi) : 0.0;
      const Point2 centre(random->Uniform(room.x_lo, room.x_hi),
                          random->Uniform(room.y_lo, room.y_hi));
      const double c = std::cos(angle);
      const double s = std::sin(angle);
      std::vector<Point2> corners;
      bool inside = true;
      for (const auto& [u, v] :
           {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}}) {
        const double lx = u * w / 2.0;
        const double ly = v * h / 2.0;
        const Point2 p = centre + Point2(c * lx - s * ly, s * lx + c * ly);
        inside = inside && p.x() > room.x_lo + margin && p.x() < room.x_hi - margin &&
                 p.y() > room.y_lo + margin && p.y() < room.y_hi - margin;
        corners.push_back(p);
      }
      if (!inside) continue;
      const double half_diagonal = std::hypot(w, h) / 2.0;
      bool clear = true;
      for (const Point2& door : keep_clear) {
        clear = clear && (door - centre).norm() > half_diagonal + 1.3;
      }
      for (const auto& [other, other_half] : placed) {
        clear = clear && (other - centre).norm() > half_diagonal + other_half + 0.7;
      }
      if (!clear) continue;
      placed.push_back({centre, half_diagonal});
      terrain->polygons.push_back({std::move(corners), ObstacleKind::kFurniture, true});
      break;
    }
  }
}

void GenerateOffice(const TerrainOptions& options, Random* random, Terrain* terrain) {
  const double size = options.size;
  const double t = options.wall_thickness;
  const double corridor = size < 8.0 ? 1.6 : 2.0;
  const int bands = std::max(1, static_cast<int>(std::lround(size / 12.0)));
  const double band = size / bands;
  const double depth = (band - corridor) / 2.0;
  constexpr double kDoorWidth = 1.2;

  // Vertical corridors (spines) joining the bands' corridors.
  std::vector<Interval> spines;
  if (bands > 1) {
    const int count = std::max(1, static_cast<int>(std::lround(size / 30.0)));
    for (int k = 0; k < count; ++k) {
      const double slot = size / count;
      const double centre = slot * (k + 0.5) + random->Uniform(-0.15, 0.15) * slot;
      spines.push_back({centre - corridor / 2.0, centre + corridor / 2.0});
    }
  }
  // The x intervals of room rows: the terrain's width minus the spines.
  std::vector<Interval> columns;
  double cursor = 0.0;
  for (const Interval& spine : spines) {
    columns.push_back({cursor, spine.lo});
    cursor = spine.hi;
  }
  columns.push_back({cursor, size});

  std::vector<Room> rooms;
  std::vector<Point2> inner_doors;
  for (int b = 0; b < bands; ++b) {
    const double y0 = b * band;
    const double corridor_lo = y0 + depth;
    const double corridor_hi = corridor_lo + corridor;
    // Two rows: below the corridor (door on its top wall) and above it (door on its bottom wall).
    const Interval rows[2] = {{y0, corridor_lo}, {corridor_hi, y0 + band}};
    for (int r = 0; r < 2; ++r) {
      const Interval row = rows[r];
      const double door_y = r == 0 ? corridor_lo : corridor_hi;
      for (const Interval& column : columns) {
        std::vector<Interval> door_gaps;
        double x = column.lo;
        while (column.hi - x > 1e-9) {
          double w = random->Uniform(3.0, 6.0);
          if (column.hi - (x + w) < 3.0) w = column.hi - x;
          Room room{x, x + w, row.lo, row.hi, Point2::Zero()};
          const double door_w = std::min(kDoorWidth, std::max(0.0, w - 0.6));
          const double lo = x + 0.3 + door_w / 2.0;
          const double hi = x + w - 0.3 - door_w / 2.0;
          const double centre = hi > lo ? random->Uniform(lo, hi) : x + w / 2.0;
          door_gaps.push_back({centre - door_w / 2.0, centre + door_w / 2.0});
          room.door = Point2(centre, door_y);
          // Partition to the next room, sometimes with a door through it.
          if (x + w < column.hi - 1e-9) {
            std::vector<Interval> gaps;
            if (row.hi - row.lo > kDoorWidth + 0.8 && random->Bernoulli(0.3)) {
              const double mid = (row.lo + row.hi) / 2.0;
              gaps.push_back({mid - kDoorWidth / 2.0, mid + kDoorWidth / 2.0});
              inner_doors.push_back(Point2(x + w, mid));
            }
            AddAxisWall(false, x + w, row.lo, row.hi, gaps, t, terrain);
          }
          rooms.push_back(room);
          x += w;
        }
        AddAxisWall(true, door_y, column.lo, column.hi, door_gaps, t, terrain);
        if (r == 1 && b + 1 < bands) {
          AddAxisWall(true, row.hi, column.lo, column.hi, {}, t, terrain);
        }
      }
      for (const Interval& spine : spines) {
        AddAxisWall(false, spine.lo, row.lo, row.hi, {}, t, terrain);
        AddAxisWall(false, spine.hi, row.lo, row.hi, {}, t, terrain);
      }
    }
  }
  for (const Room& room : rooms) {
    std::vector<Point2> keep_clear = {room.door};
    for (const Point2& door : inner_doors) {
      if (door.x() >= room.x_lo - 0.01 && door.x() <= room.x_hi + 0.01 && door.y() >= room.y_lo &&
          door.y() <= room.y_hi) {
        keep_clear.push_back(door);
      }
    }
    AddFurniture(room, keep_clear, t, random, terrain);
  }
  terrain->start = {std::min(1.0, size / 4.0), depth + corridor / 2.0, 0.0};
}

// ---- unstructured -----------------------------------------------------------------------------

// Disks covering the obstacles placed so far, bucketed on a coarse grid for the clearance test.
class DiskIndex {
 public:
  explicit DiskIndex(double bucket) : bucket_(bucket) {}

  bool Fits(const std::vector<std::pair<Point2, double>>& disks, double clearance, double lo,
            double hi) const {
    for (const auto& [c, r] : disks) {
      if (c.x() - r < lo || c.y() - r < lo || c.x() + r > hi || c.y() + r > hi) return false;
      const int reach = static_cast<int>(std::ceil((r + clearance + max_radius_) / bucket_));
      const int bx = Bucket(c.x());
      const int by = Bucket(c.y());
      for (int y = by - reach; y <= by + reach; ++y) {
        for (int x = bx - reach; x <= bx + reach; ++x) {
          const auto it = buckets_.find(Key(x, y));
          if (it == buckets_.end()) continue;
          for (const auto& [oc, orad] : it->second) {
            if ((oc - c).norm() < r + orad + clearance) return false;
          }
        }
      }
    }
    return true;
  }

  void Add(const std::vector<std::pair<Point2, double>>& disks) {
    for (const auto& disk : disks) {
      buckets_[Key(Bucket(disk.first.x()), Bucket(disk.first.y()))].push_back(disk);
      max_radius_ = std::max(max_radius_, disk.second);
    }
  }

 private:
  int Bucket(double v) const { return static_cast<int>(std::floor(v / bucket_)); }
  static int64_t Key(int x, int y) { return (static_cast<int64_t>(x) << 32) ^ (y & 0xFFFFFFFF); }

  double bucket_;
  double max_radius_ = 0.0;
  std::unordered_map<int64_t, std::vector<std::pair<Point2, double>>> buckets_;
};

// Disks every 0.3 m along a thick segment.
void SegmentDisks(const Point2& a, const Point2& b, double radius,
                  std::vector<std::pair<Point2, double>>* disks) {
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.3)));
  for (int i = 0; i <= steps; ++i) {
    disks->push_back({a + (b - a) * (static_cast<double>(i) / steps), radius + 0.15});
  }
}

void GenerateUnstructured(const TerrainOptions& options, Random* random, Terrain* terrain) {
  const double size = options.size;
  const double area = size * size;
  constexpr double kClearance = 1.3;  // any two obstacles: the robot (and the free space) passes
  const double lo = options.boundary_thickness + kClearance;
  const double hi = size - lo;
  DiskIndex index(2.0);
  terrain->start = {size / 2.0, size / 2.0, random->Uniform(-kPi, kPi)};
  index.Add({{terrain->start.translation(), 0.8}});

  const int want_rubble = std::max(2, static_cast<int>(std::lround(area / 10.0)));
  const int want_diagonal = std::max(1, static_cast<int>(std::lround(area / 60.0)));
  const int want_arc = std::max(1, static_cast<int>(std::lround(area / 90.0)));
  int rubble = 0, diagonal = 0, arc = 0;
  const int attempts = 12 * (want_rubble + want_diagonal + want_arc);
  for (int attempt = 0; attempt < attempts; ++attempt) {
    const double pick = random->Uniform();
    const Point2 centre(random->Uniform(lo, hi), random->Uniform(lo, hi));
    std::vector<std::pair<Point2, double>> disks;
    if (pick < 0.6) {
      if (rubble >= want_rubble) continue;
      const double radius = random->Uniform(0.25, 1.0);
      const int n = random->UniformInt(5, 9);
      std::vector<Point2> points;
      for (int i = 0; i < n; ++i) {
        const double angle = (i + random->Uniform(-0.3, 0.3)) * 2.0 * kPi / n;
        const double r = radius * random->Uniform(0.55, 1.0);
        points.push_back(centre + r * Point2(std::cos(angle), std::sin(angle)));
      }
      disks.push_back({centre, radius});
      if (!index.Fits(disks, kClearance, lo, hi)) continue;
      index.Add(disks);
      terrain->polygons.push_back({std::move(points), ObstacleKind::kRubble, false});
      ++rubble;
    } else if (pick < 0.8) {
      if (diagonal >= want_diagonal) continue;
      const double length = random->Uniform(2.0, std::max(2.5, std::min(8.0, size / 3.0)));
      const double angle = random->Uniform(0.0, kPi);
      const double thickness = random->Uniform(0.15, 0.3);
      const Point2 half = length / 2.0 * Point2(std::cos(angle), std::sin(angle));
      SegmentDisks(centre - half, centre + half, thickness / 2.0, &disks);
      if (!index.Fits(disks, kClearance, lo, hi)) continue;
      index.Add(disks);
      terrain->walls.push_back({centre - half, centre + half, thickness, ObstacleKind::kWall});
      ++diagonal;
    } else {
      if (arc >= want_arc) continue;
      const double radius = random->Uniform(1.5, std::max(2.0, std::min(5.0, size / 5.0)));
      const double start = random->Uniform(0.0, 2.0 * kPi);
      const double span = random->Uniform(kPi / 3.0, 1.2 * kPi);
      const int pieces = std::max(3, static_cast<int>(std::ceil(span * radius / 0.4)));
      std::vector<Point2> points;
      for (int i = 0; i <= pieces; ++i) {
        const double angle = start + span * i / pieces;
        points.push_back(centre + radius * Point2(std::cos(angle), std::sin(angle)));
      }
      for (int i = 0; i < pieces; ++i) {
        SegmentDisks(points[i], points[i + 1], options.wall_thickness / 2.0, &disks);
      }
      if (!index.Fits(disks, kClearance, lo, hi)) continue;
      index.Add(disks);
      for (int i = 0; i < pieces; ++i) {
        terrain->walls.push_back(
            {points[i], points[i + 1], options.wall_thickness, ObstacleKind::kWall});
      }
      ++arc;
    }
    if (rubble >= want_rubble && diagonal >= want_diagonal && arc >= want_arc) break;
  }
}

void GenerateWarehouse(const TerrainOptions& options, Random* random, Terrain* terrain) {
  AddWarehouse(options.size, random, terrain);
}

}  // namespace

void AddWarehouse(double size, Random* random, Terrain* terrain) {
  const auto add_box = [terrain](double x0, double y0, double x1, double y1, ObstacleKind kind) {
    terrain->polygons.push_back({{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, kind});
  };
  const double depth = random->Uniform(0.9, 1.2);    // rack depth
  const double period = random->Uniform(3.0, 3.8);   // rack + aisle
  const double margin = random->Uniform(2.5, 3.5);   // front / back aisles and the side aisles
  const double cross = random->Uniform(0.35, 0.65);  // where the cross aisle runs (share of x)
  const double cross_width = random->Uniform(2.5, 3.5);
  const double x0 = margin, x1 = size - margin;
  const double cross_x = x0 + cross * (x1 - x0 - cross_width);
  std::vector<double> row_ys;
  for (double y = margin; y + depth <= size - margin; y += period) row_ys.push_back(y);
  for (const double y : row_ys) {
    add_box(x0, y, cross_x, y + depth, ObstacleKind::kFurniture);
    add_box(cross_x + cross_width, y, x1, y + depth, ObstacleKind::kFurniture);
  }
  // Pillars every 6 m along the front and back aisles, 0.4 m square.
  for (double x = x0; x <= x1; x += 6.0) {
    for (const double y : {margin / 2.0, size - margin / 2.0}) {
      add_box(x - 0.2, y - 0.2, x + 0.2, y + 0.2, ObstacleKind::kWall);
    }
  }
  // A few pallets, each in a random aisle between two rows, against a rack: the only thing that
  // tells two aisles apart.
  const int pallets = random->UniformInt(2, 5);
  for (int k = 0; k + 1 < static_cast<int>(row_ys.size()) && k < pallets; ++k) {
    const int row = random->UniformInt(0, static_cast<int>(row_ys.size()) - 2);
    const double y = row_ys[row] + depth + 0.1;
    const double x = random->Uniform(x0, x1 - 1.2);
    const double side = random->Uniform(0.8, 1.2);
    add_box(x, y, x + side, y + side * 0.8, ObstacleKind::kFurniture);
  }
  terrain->start = {size / 2.0, margin / 2.0 + 0.8, 0.0};
}

StatusOr<TerrainGenerator> TerrainGenerator::Create(const TerrainOptions& options) {
  if (!(options.size >= kMinTerrainSize && options.size <= kMaxTerrainSize)) {
    return InvalidArgumentError(
        "terrain size " + ShortNumber(options.size) + " m is out of bounds: it must be in [" +
        ShortNumber(kMinTerrainSize) + ", " + ShortNumber(kMaxTerrainSize) + "] m");
  }
  if (!(options.wall_thickness > 0.0 && options.wall_thickness <= 1.0)) {
    return InvalidArgumentError("terrain wall_thickness must be in (0, 1] m");
  }
  if (!(options.boundary_thickness > 0.0 && options.boundary_thickness <= 1.0)) {
    return InvalidArgumentError("terrain boundary_thickness must be in (0, 1] m");
  }
  return TerrainGenerator(options);
}

Terrain TerrainGenerator::Generate() const {
  Terrain terrain;
  terrain.kind = options_.kind;
  terrain.size = options_.size;
  terrain.seed = options_.seed;
  // Each kind draws from its own stream of the seed.
  Random random(options_.seed * 2654435761u + static_cast<uint32_t>(options_.kind));
  AddBoundary(options_.size, options_.boundary_thickness, &terrain);
  switch (options_.kind) {
    case TerrainKind::kMaze:
      GenerateMaze(options_, &random, &terrain);
      break;
    case TerrainKind::kOffice:
      GenerateOffice(options_, &random, &terrain);
      break;
    case TerrainKind::kUnstructured:
      GenerateUnstructured(options_, &random, &terrain);
      break;
    case TerrainKind::kWarehouse:
      GenerateWarehouse(options_, &random, &terrain);
      break;
  }
  return terrain;
}

}  // namespace fleetmap::sim
