#include "bench/register/repeated_terrain.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/core/check.hpp"
#include "common/sim/random.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {
namespace {

using sim::ObstacleKind;
using sim::Terrain;

constexpr double kBoundary = 0.2;  // metres, the outer wall
constexpr double kWall = 0.15;     // metres, interior walls

void AddBox(double x0, double y0, double x1, double y1, ObstacleKind kind, Terrain* terrain) {
  terrain->polygons.push_back({{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, kind});
}

// A horizontal wall at `y` from x0 to x1 with door gaps [gap, gap + width) at `gaps`.
void AddWallWithGaps(double y, double x0, double x1, const std::vector<double>& gaps, double width,
                     Terrain* terrain) {
  double cursor = x0;
  for (const double gap : gaps) {
    if (gap > cursor) terrain->walls.push_back({{cursor, y}, {gap, y}, kWall, ObstacleKind::kWall});
    cursor = gap + width;
  }
  if (x1 > cursor) terrain->walls.push_back({{cursor, y}, {x1, y}, kWall, ObstacleKind::kWall});
}

// Two bands of identical rooms on either side of a corridor; a west corridor joins the bands.
void OfficeRows(double size, sim::Random* random, Terrain* terrain) {
  const double room_width = random->Uniform(3.2, 4.5);
  const double room_depth = random->Uniform(4.0, 5.0);
  const double corridor = random->Uniform(1.8, 2.4);
  const double door = 0.9;
  const double door_offset = random->Uniform(0.3, room_width - door - 0.3);
  const double west = kBoundary + corridor;  // the west corridor's east side
  const double east = size - kBoundary;
  std::vector<double> partitions;  // room walls' x
  for (double x = west; x + room_width <= east; x += room_width) partitions.push_back(x);
  std::vector<double> door_xs;
  for (const double x : partitions) door_xs.push_back(x + door_offset);
  double y = kBoundary;
  while (y + 2.0 * room_depth + corridor <= size - kBoundary + 1e-9) {
    const double corridor_lo = y + room_depth, corridor_hi = corridor_lo + corridor;
    const double top = corridor_hi + room_depth;
    // The rooms' back walls, the corridor's walls (with doors), the partitions.
    AddWallWithGaps(corridor_lo, west, east, door_xs, door, terrain);
    AddWallWithGaps(corridor_hi, west, east, door_xs, door, terrain);
    if (top < size - kBoundary - 0.5) AddWallWithGaps(top, west, east, {}, door, terrain);
    for (const double x : partitions) {
      terrain->walls.push_back({{x, y}, {x, corridor_lo}, kWall, ObstacleKind::kWall});
      terrain->walls.push_back({{x, corridor_hi}, {x, top}, kWall, ObstacleKind::kWall});
    }
    // A desk against the back wall of some rooms.
    for (const double x : partitions) {
      for (const double back : {y, top}) {
        if (!random->Bernoulli(0.3)) continue;
        const double dx = random->Uniform(0.4, room_width - 1.6);
        const double y0 = back == y ? y + 0.3 : top - 1.0;
        AddBox(x + dx, y0, x + dx + 1.2, y0 + 0.7, ObstacleKind::kFurniture, terrain);
      }
    }
    y = top;
  }
  terrain->start = {kBoundary + corridor / 2.0, size / 2.0, 0.0};
}

// A Manhattan grid of corridors around identical solid blocks; a few cabinets against them.
void Corridors(double size, sim::Random* random, Terrain* terrain) {
  const double corridor = random->Uniform(1.8, 2.4);
  const double block_w = random->Uniform(4.0, 7.0);
  const double block_h = random->Uniform(3.0, 6.0);
  std::vector<Point2> corners;  // blocks' lower-left corners
  for (double x = kBoundary + corridor; x + block_w <= size - kBoundary - corridor;
       x += block_w + corridor) {
    for (double y = kBoundary + corridor; y + block_h <= size - kBoundary - corridor;
         y += block_h + corridor) {
      corners.emplace_back(x, y);
    }
  }
  FLEETMAP_CHECK(!corners.empty(), "RepeatedTerrain: the corridors terrain has no block");
  for (const Point2& c : corners) {
    AddBox(c.x(), c.y(), c.x() + block_w, c.y() + block_h, ObstacleKind::kWall, terrain);
  }
  // Cabinets, 0.4 m deep, against the south face of a few blocks.
  const int cabinets = random->UniformInt(2, 5);
  for (int k = 0; k < cabinets; ++k) {
    const Point2& c = corners[random->UniformInt(0, static_cast<int>(corners.size()) - 1)];
    const double x = c.x() + random->Uniform(0.3, block_w - 0.7);
    AddBox(x, c.y() - 0.4, x + 0.4, c.y(), ObstacleKind::kFurniture, terrain);
  }
  terrain->start = {kBoundary + corridor / 2.0, kBoundary + corridor / 2.0, 0.0};
}

}  // namespace

std::string_view RepeatedKindName(RepeatedKind kind) {
  switch (kind) {
    case RepeatedKind::kWarehouse:
      return "warehouse";
    case RepeatedKind::kOfficeRows:
      return "office_rows";
    case RepeatedKind::kCorridors:
      return "corridors";
  }
  return "unknown";
}

sim::Terrain RepeatedTerrain(RepeatedKind kind, double size, uint32_t seed) {
  FLEETMAP_CHECK(size >= 20.0, "RepeatedTerrain needs at least 20 m");
  sim::Random random(seed);
  Terrain terrain;
  terrain.size = size;
  terrain.seed = seed;
  sim::AddBoundary(size, kBoundary, &terrain);
  switch (kind) {
    case RepeatedKind::kWarehouse:
      sim::AddWarehouse(size, &random, &terrain);
      break;
    case RepeatedKind::kOfficeRows:
      OfficeRows(size, &random, &terrain);
      break;
    case RepeatedKind::kCorridors:
      Corridors(size, &random, &terrain);
      break;
  }
  return terrain;
}

}  // namespace fleetmap::bench
