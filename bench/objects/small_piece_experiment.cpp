#include "bench/objects/small_piece_experiment.hpp"

#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "bench/report/report_format.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/object_learning/snapshot_extractor.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::bench {
namespace {

constexpr int kWidth = 400;  // cells: 20 x 15 m at 5 cm
constexpr int kHeight = 300;
constexpr double kResolution = 0.05;
constexpr int kWall = 2;               // cells of wall all round
constexpr double kSpacing = 0.6;       // metres between pieces, and from the walls
constexpr double kFoundWithin = 0.15;  // metres from a piece's centre

using Shape = std::vector<std::pair<int, int>>;

grid::OccupancyGrid Floor() {
  grid::OccupancyGrid map(kWidth, kHeight, kResolution, Pose2{}, grid::kFreeValue);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (x < kWall || y < kWall || x >= kWidth - kWall || y >= kHeight - kWall) {
        map.at(x, y) = grid::kOccupiedValue;
      }
    }
  }
  return map;
}

double FreeArea() {
  return (kWidth - 2 * kWall) * (kHeight - 2 * kWall) * kResolution * kResolution;
}

Shape SmallShape(int kind) {
  switch (kind) {
    case 0:
      return {{0, 0}, {1, 0}, {0, 1}, {1, 1}};  // 2 x 2
    case 1:
      return {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};  // plus sign
    case 2:
      return {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 2}, {1, 2}};  // 2 x 3
    default:
      return {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {0, 2}};  // L of 7
  }
}

Shape Rectangle(int w, int h) {
  Shape shape;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) shape.emplace_back(x, y);
  }
  return shape;
}

// A piece drawn in one map: its cells' centre (metres) and size.
struct Instance {
  int map = 0;
  Point2 centre = Point2::Zero();
  bool small = false;
  bool found = false;
};

// Paints `shape` at cell (x, y); returns the painted cells' centre.
Point2 Paint(grid::OccupancyGrid* map, const Shape& shape, int x, int y) {
  Point2 sum = Point2::Zero();
  for (const auto& [dx, dy] : shape) {
    map->at(x + dx, y + dy) = grid::kOccupiedValue;
    sum += map->CellCenter(x + dx, y + dy);
  }
  return sum / static_cast<double>(shape.size());
}

// A cell position at least kSpacing from the walls and from every position in `taken`.
std::pair<int, int> FreePlace(std::vector<Point2>* taken, sim::Random* random) {
  const int margin = static_cast<int>(std::ceil(kSpacing / kResolution)) + kWall;
  for (int attempt = 0;; ++attempt) {
    const int x = random->UniformInt(margin, kWidth - margin - 20);
    const int y = random->UniformInt(margin, kHeight - margin - 20);
    const Point2 p((x + 0.5) * kResolution, (y + 0.5) * kResolution);
    bool clear = true;
    for (const Point2& q : *taken) clear = clear && (p - q).norm() >= kSpacing + 1.0;
    if (clear || attempt > 2000) {
      taken->push_back(p);
      return {x, y};
    }
  }
}

// SLAM specks in free space (the header says which).
void AddSpecks(grid::OccupancyGrid* map, double events_per_100m2, sim::Random* random) {
  const double expected = events_per_100m2 * FreeArea() / 100.0;
  int events = static_cast<int>(std::floor(expected));
  events += random->Bernoulli(expected - events);
  const auto set = [map](int x, int y) {
    if (x >= kWall && y >= kWall && x < kWidth - kWall && y < kHeight - kWall) {
      map->at(x, y) = grid::kOccupiedValue;
    }
  };
  for (int e = 0; e < events; ++e) {
    const int x = random->UniformInt(kWall, kWidth - kWall - 1);
    const int y = random->UniformInt(kWall, kHeight - kWall - 1);
    const double kind = random->Uniform();
    if (kind < 0.5) {  // scatter
      const int n = random->UniformInt(3, 8);
      const int r = static_cast<int>(std::lround(0.4 / kResolution));
      for (int k = 0; k < n;) {
        const int dx = random->UniformInt(-r, r), dy = random->UniformInt(-r, r);
        if (dx * dx + dy * dy > r * r) continue;
        set(x + dx, y + dy);
        ++k;
      }
    } else if (kind < 0.8) {  // strand
      const int n = random->UniformInt(4, 8);
      const bool along_x = random->Bernoulli(0.5);
      for (int k = 0; k < n; ++k) set(along_x ? x + k : x, along_x ? y : y + k);
    } else {  // blob
      const int n = random->UniformInt(2, 4);
      int cx = x, cy = y;
      for (int k = 0; k < n; ++k) {
        set(cx, cy);
        const int step = random->UniformInt(0, 3);
        cx += step == 0 ? 1 : step == 1 ? -1 : 0;
        cy += step == 2 ? 1 : step == 3 ? -1 : 0;
      }
    }
  }
}

}  // namespace

grid::OccupancyGrid SpeckledFloor(double events_per_100m2, sim::Random* random) {
  grid::OccupancyGrid map = Floor();
  AddSpecks(&map, events_per_100m2, random);
  return map;
}

StatusOr<SmallPieceResult> RunSmallPieceExperiment(const SmallPieceOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.snapshots.Validate());
  if (options.pairs < 1 || options.pairs > 1000 || options.furniture < 0 ||
      options.small_pieces < 0 || options.furniture + options.small_pieces > 60 ||
      !(options.speck_events_per_100m2 >= 0.0 && options.speck_events_per_100m2 <= 100.0)) {
    return InvalidArgumentError(
        "small pieces: pairs in [1, 1000], at most 60 pieces a pair, speck events per 100 m2 in "
        "[0, 100]");
  }
  SmallPieceResult result;
  for (int p = 0; p < options.pairs; ++p) {
    sim::Random random(options.seed * 7919u + static_cast<uint32_t>(p) * 104729u + 17u);
    // The furnished pair.
    std::vector<grid::OccupancyGrid> maps = {Floor(), Floor()};
    std::vector<Instance> instances;
    std::vector<Point2> taken;
    for (int k = 0; k < options.furniture + options.small_pieces; ++k) {
      const bool small = k >= options.furniture;
      const Shape shape = small ? SmallShape(random.UniformInt(0, 3))
                                : Rectangle(random.UniformInt(4, 16), random.UniformInt(3, 12));
      int mode = random.UniformInt(0, 2);  // in map 0 only, map 1 only, moved
      if (small && options.small_in_one_map) mode = 0;
      for (int m = 0; m < 2; ++m) {
        if (mode != 2 && mode != m) continue;
        const auto [x, y] = FreePlace(&taken, &random);
        instances.push_back({m, Paint(&maps[m], shape, x, y), small, false});
      }
    }
    for (grid::OccupancyGrid& map : maps) {
      AddSpecks(&map, options.speck_events_per_100m2, &random);
    }
    FLEETMAP_ASSIGN_OR_RETURN(const object_learning::SnapshotSet set,
                              object_learning::ExtractSnapshots(maps, options.snapshots));
    for (const object_learning::Snapshot& s : set.snapshots) {
      ++result.snapshots;
      bool matched = false;
      for (Instance& i : instances) {
        if (i.map == s.map_index && (i.centre - s.centre).norm() <= kFoundWithin) {
          i.found = matched = true;
        }
      }
      result.false_objects += !matched;
    }
    for (const Instance& i : instances) {
      (i.small ? result.small : result.furniture) += 1;
      (i.small ? result.small_found : result.furniture_found) += i.found;
    }
    // The noise-only pair.
    std::vector<grid::OccupancyGrid> noise;
    for (int m = 0; m < 2; ++m) {
      noise.push_back(SpeckledFloor(options.speck_events_per_100m2, &random));
      result.noise_census.Add(CountLoneSpecks(noise.back()));
    }
    FLEETMAP_ASSIGN_OR_RETURN(const object_learning::SnapshotSet noise_set,
                              object_learning::ExtractSnapshots(noise, options.snapshots));
    result.noise_snapshots += static_cast<int>(noise_set.snapshots.size());
    result.noise_area_m2 += FreeArea();
  }
  return result;
}

std::string SmallPieceReport(const SmallPieceOptions& options, const SmallPieceResult& r) {
  const auto ratio = [](int a, int b) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(3);
    if (b == 0) return std::string("n/a");
    s << static_cast<double>(a) / b;
    return s.str();
  };
  std::ostringstream md;
  md.setf(std::ios::fixed);
  md.precision(2);
  md << "# Small objects against SLAM specks\n\n"
     << "Command: `fleetmap bench objects --small-pieces " << options.pairs << " --seed "
     << options.seed << (options.small_in_one_map ? " --small-in-one-map" : "")
     << " --speck-events " << options.speck_events_per_100m2 << " --isolation-radius "
     << options.snapshots.isolation_radius_m << "`  \nMachine: " << MachineDescription()
     << ", Release build.\n\n"
     << "Per pair: a 20 x 15 m floor at 5 cm (" << FreeArea() << " m2 free), " << options.furniture
     << " pieces of furniture and " << options.small_pieces << " small pieces (4-7 cells), "
     << (options.small_in_one_map ? "the small pieces in map 0 only, the furniture" : "each")
     << " in one map only or moved; specks in both maps (" << options.speck_events_per_100m2
     << " events per 100 m2 per map). A noise-only pair: specks only.\n\n"
     << "| pairs | small pieces found | recall (4-7 cells) | furniture found | recall (furniture) "
        "| snapshots | false objects | precision | noise-only pairs: false objects | per 100 m2 "
        "|\n|---|---|---|---|---|---|---|---|---|---|\n"
     << "| " << options.pairs << " | " << r.small_found << " / " << r.small << " | "
     << ratio(r.small_found, r.small) << " | " << r.furniture_found << " / " << r.furniture << " | "
     << ratio(r.furniture_found, r.furniture) << " | " << r.snapshots << " | " << r.false_objects
     << " | " << ratio(r.snapshots - r.false_objects, r.snapshots) << " | " << r.noise_snapshots
     << " | " << (r.noise_area_m2 > 0.0 ? 100.0 * r.noise_snapshots / r.noise_area_m2 : 0.0)
     << " |\n\n"
     << "Census of the noise-only maps (bench/objects/speck_census.hpp), per 100 m2: "
     << r.noise_census.Per100m2(r.noise_census.lone_specks) << " lone specks of 1-3 cells, "
     << r.noise_census.Per100m2(r.noise_census.lone_clusters) << " lone clusters of 4-8, "
     << r.noise_census.Per100m2(r.noise_census.lone_compact) << " of them compact.\n";
  return md.str();
}

}  // namespace fleetmap::bench
