#include "common/sim/indoor_scene_generator.hpp"

#include <algorithm>
#include <cmath>

#include "common/sim/random.hpp"

namespace fleetmap::sim {
namespace {

SolidPolygon Rectangle(const Point2& lo, const Point2& hi, ObstacleKind kind, bool movable) {
  return {{lo, Point2(hi.x(), lo.y()), hi, Point2(lo.x(), hi.y())}, kind, movable};
}

struct RoomRow {
  double y_wall;  // centre line of the corridor wall this row opens on
  double y_far;   // the far face of the rooms (the building's outer wall face)
  double sign;    // +1: rooms above the corridor, -1: below
};

}  // namespace

IndoorScene GenerateIndoorScene(const IndoorSceneOptions& options, uint32_t seed) {
  Random random(seed);
  IndoorScene scene;
  const double t = options.wall_thickness;
  const double boundary = 0.2;
  scene.wall_height = options.wall_height;

  const double corridor_width = random.Uniform(1.5, 2.0);
  const double depth_below = random.Uniform(4.0, 5.5);
  const double depth_above = random.Uniform(4.0, 5.5);
  SceneStairs& stairs = scene.stairs;
  stairs.width = corridor_width;
  stairs.tread = random.Uniform(0.27, 0.30);
  const double floor_height = options.floor_height + random.Uniform(-0.1, 0.1);
  stairs.risers = static_cast<int>(std::lround(floor_height / 0.17));
  stairs.rise = floor_height / stairs.risers;
  const double hall_length = random.Uniform(1.5, 4.5);
  stairs.block_length = hall_length;

  // y: outer wall face at 0.1, rooms below, corridor, rooms above, outer wall.
  const double y_wall_low = 0.5 * boundary + depth_below + 0.5 * t;
  const double y_corridor_lo = y_wall_low + 0.5 * t;
  const double y_corridor_hi = y_corridor_lo + corridor_width;
  const double y_wall_high = y_corridor_hi + 0.5 * t;
  const double y_top = y_wall_high + 0.5 * t + depth_above + 0.5 * boundary;
  const double x_foot = 0.5 * boundary + options.corridor_length;
  stairs.foot = Point2(x_foot, 0.5 * (y_corridor_lo + y_corridor_hi));
  stairs.ascending = Vector2::UnitX();
  const double x_end = stairs.top().x() + hall_length + 0.5 * boundary;
  const double size = std::ceil(std::max(x_end, y_top) + 0.5);
  scene.corridor_min = Point2(0.5 * boundary, y_corridor_lo);
  scene.corridor_max = Point2(x_foot, y_corridor_hi);

  Terrain& ground = scene.ground;
  ground.kind = TerrainKind::kOffice;
  ground.size = size;
  ground.seed = seed;
  auto wall = [](Terrain* terrain, Point2 a, Point2 b, double thickness, ObstacleKind kind) {
    terrain->walls.push_back({a, b, thickness, kind, false});
  };
  // The building's outline and the filler outside it (the rest of the square).
  for (Terrain* terrain : {&scene.ground, &scene.upper}) {
    terrain->size = size;
    terrain->seed = seed;
    wall(terrain, {0, 0}, {x_end, 0}, boundary, ObstacleKind::kBoundary);
    wall(terrain, {0, 0}, {0, y_top}, boundary, ObstacleKind::kBoundary);
    wall(terrain, {0, y_top}, {x_end, y_top}, boundary, ObstacleKind::kBoundary);
    wall(terrain, {x_end, 0}, {x_end, y_top}, boundary, ObstacleKind::kBoundary);
    if (x_end < size)
      terrain->polygons.push_back(Rectangle({x_end, 0}, {size, size}, ObstacleKind::kWall, false));
    if (y_top < size)
      terrain->polygons.push_back(Rectangle({0, y_top}, {x_end, size}, ObstacleKind::kWall, false));
  }
  for (size_t i = 0; i < ground.polygons.size(); ++i) scene.polygon_heights.push_back(3.0);

  // The stairs' footprint (and the block under the landing) fills the corridor's east end.
  ground.polygons.push_back(
      Rectangle({x_foot, y_corridor_lo}, {x_end, y_corridor_hi}, ObstacleKind::kWall, false));
  scene.polygon_heights.push_back(0.0);  // drawn as steps by SceneBoxes, not as a box
  // The corridor's east end beyond the flight is the building's end wall (already there).

  const RoomRow rows[2] = {{y_wall_low, 0.5 * boundary, -1.0},
                           {y_wall_high, y_top - 0.5 * boundary, +1.0}};
  std::vector<Point2> furniture_keep_out;
  for (const RoomRow& row : rows) {
    // Room boundaries along x, from the west wall to the end of the building.
    std::vector<double> xs = {0.5 * boundary};
    while (xs.back() < x_end - 0.5 * boundary - 3.0) {
      double w = random.Uniform(3.0, 5.5);
      if (x_end - 0.5 * boundary - (xs.back() + w) < 3.0) w = x_end - 0.5 * boundary - xs.back();
      xs.push_back(xs.back() + w);
    }
    xs.back() = x_end - 0.5 * boundary;
    // Walls between rooms.
    for (size_t i = 1; i + 1 < xs.size(); ++i) {
      wall(&ground, {xs[i], row.y_wall}, {xs[i], row.y_far}, t, ObstacleKind::kWall);
    }
    // The corridor wall, with a door for each room whose doorway lies west of the stairs.
    double wall_start = 0.0;
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
      const double lo = xs[i] + 0.5 * t, hi = xs[i + 1] - 0.5 * t;
      const double door_width = random.Uniform(0.85, 1.0);
      const double door_x = random.Uniform(lo + 0.3, hi - door_width - 0.3);
      const bool has_door = door_x + door_width < x_foot - 0.5;
      if (has_door) {
        wall(&ground, {wall_start, row.y_wall}, {door_x, row.y_wall}, t, ObstacleKind::kWall);
        wall_start = door_x + door_width;
        SceneDoor door;
        const bool hinge_west = random.Bernoulli(0.5);
        const Point2 west(door_x, row.y_wall), east(door_x + door_width, row.y_wall);
        door.hinge = hinge_west ? west : east;
        door.latch = hinge_west ? east : west;
        door.room_side = Vector2(0.0, row.sign);
        door.height = random.Uniform(2.0, 2.1);
        door.wall_thickness = t;
        door.open = !random.Bernoulli(options.closed_door_probability);
        scene.doors.push_back(door);
        ground.doors.push_back({west, east, door.open, t});
        furniture_keep_out.push_back(door.center());
      }
      // Furniture: 0-3 pieces, away from the door and the walls.
      const int pieces = random.UniformInt(0, 3);
      const double y_near = row.y_wall + row.sign * 0.5 * t;
      for (int k = 0; k < pieces; ++k) {
        for (int attempt = 0; attempt < 10; ++attempt) {
          const double fw = random.Uniform(0.6, 1.6), fd = random.Uniform(0.5, 0.9);
          const bool turned = random.Bernoulli(0.5);
          const double sx = turned ? fd : fw, sy = turned ? fw : fd;
          const double cx = random.Uniform(lo + 0.15 + 0.5 * sx, hi - 0.15 - 0.5 * sx);
          const double ylo = std::min(y_near, row.y_far), yhi = std::max(y_near, row.y_far);
          if (yhi - ylo < sy + 0.3 || hi - lo < sx + 0.3) break;
          const double cy = random.Uniform(ylo + 0.15 + 0.5 * sy, yhi - 0.15 - 0.5 * sy);
          bool clear = true;
          for (const Point2& keep : furniture_keep_out) {
            const double dx = std::max(0.0, std::abs(keep.x() - cx) - 0.5 * sx);
            const double dy = std::max(0.0, std::abs(keep.y() - cy) - 0.5 * sy);
            if (std::hypot(dx, dy) < 1.3) clear = false;
          }
          if (!clear) continue;
          ground.polygons.push_back(Rectangle({cx - 0.5 * sx, cy - 0.5 * sy},
                                              {cx + 0.5 * sx, cy + 0.5 * sy},
                                              ObstacleKind::kFurniture, true));
          scene.polygon_heights.push_back(random.Bernoulli(0.3) ? 1.8 : 0.75);
          break;
        }
      }
    }
    wall(&ground, {wall_start, row.y_wall}, {x_end, row.y_wall}, t, ObstacleKind::kWall);
  }

  // Upper floor: a hall beyond the top of the flight, a little wider than it.
  const double x_top = stairs.top().x();
  const double half = 0.5 * corridor_width + random.Uniform(0.0, 1.5);
  const double yc = stairs.foot.y();
  scene.hall_min = Point2(x_top, std::max(0.5 * boundary, yc - half));
  scene.hall_max = Point2(x_end - 0.5 * boundary, std::min(y_top - 0.5 * boundary, yc + half));
  Terrain& upper = scene.upper;
  upper.kind = TerrainKind::kOffice;
  wall(&upper, {x_top, scene.hall_min.y() - 0.5 * t}, {x_end, scene.hall_min.y() - 0.5 * t}, t,
       ObstacleKind::kWall);
  wall(&upper, {x_top, scene.hall_max.y() + 0.5 * t}, {x_end, scene.hall_max.y() + 0.5 * t}, t,
       ObstacleKind::kWall);
  const int benches = random.UniformInt(0, 2);
  for (int k = 0; k < benches; ++k) {
    const double bw = random.Uniform(0.8, 1.4), bd = random.Uniform(0.4, 0.6);
    if (scene.hall_max.x() - x_top < 1.0 + bw + 0.2) break;
    const double cx = random.Uniform(x_top + 1.0 + 0.5 * bw, scene.hall_max.x() - 0.1 - 0.5 * bw);
    const bool north = random.Bernoulli(0.5);
    const double cy =
        north ? scene.hall_max.y() - 0.05 - 0.5 * bd : scene.hall_min.y() + 0.05 + 0.5 * bd;
    upper.polygons.push_back(Rectangle({cx - 0.5 * bw, cy - 0.5 * bd},
                                       {cx + 0.5 * bw, cy + 0.5 * bd}, ObstacleKind::kFurniture,
                                       true));
  }
  ground.start = Pose2{0.5 * boundary + 1.0, yc, 0.0};
  upper.start = Pose2{x_top + 0.5, yc, 0.0};
  return scene;
}

}  // namespace fleetmap::sim
