#include "common/sim/indoor_scene.hpp"

#include <cmath>

#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::sim {
namespace {

Box3 SegmentBox(const Point2& a, const Point2& b, double thickness, double z_min, double z_max) {
  const Vector2 d = b - a;
  return {0.5 * (a + b), std::atan2(d.y(), d.x()), 0.5 * d.norm(), 0.5 * thickness, z_min, z_max};
}

// The bounding box of a polygon, as an upright box (furniture and footprints are rectangles).
Box3 PolygonBox(const SolidPolygon& polygon, double height) {
  // Rectangles are stored corner by corner: their first edge gives the orientation.
  const Point2& p0 = polygon.points[0];
  const Point2& p1 = polygon.points[1];
  const Point2& p2 = polygon.points[2];
  const Vector2 u = p1 - p0, v = p2 - p1;
  return {0.5 * (p0 + p2), std::atan2(u.y(), u.x()), 0.5 * u.norm(), 0.5 * v.norm(), 0.0, height};
}

}  // namespace

std::vector<Box3> SceneBoxes(const IndoorScene& scene) {
  std::vector<Box3> boxes;
  for (const Wall& wall : scene.ground.walls) {
    // Not extended at the ends: a wall that ends at a doorway must not narrow it (walls meet at
    // centre lines, so corners stay closed from inside).
    boxes.push_back(SegmentBox(wall.a, wall.b, wall.thickness, 0.0, scene.wall_height));
  }
  for (size_t i = 0; i < scene.ground.polygons.size(); ++i) {
    if (scene.ground.polygons[i].points.size() != 4 || !(scene.polygon_heights[i] > 0.0)) {
      continue;
    }
    boxes.push_back(PolygonBox(scene.ground.polygons[i], scene.polygon_heights[i]));
  }
  for (const SceneDoor& door : scene.doors) {
    const Vector2 along = (door.latch - door.hinge).normalized();
    const Vector2 normal = door.room_side;
    boxes.push_back(
        SegmentBox(door.hinge, door.latch, door.wall_thickness, door.height, scene.wall_height));
    // The leaf, and a handle on each face: a rose and a lever 5-19 cm from the latch edge,
    // standing 3-7 cm off the leaf.
    Point2 leaf_a = door.hinge, leaf_b = door.latch;
    Vector2 leaf_along = along, leaf_normal = normal;
    if (door.open) {
      leaf_b = door.hinge + door.width() * normal;
      leaf_along = normal;
      leaf_normal = -along;
    }
    boxes.push_back(SegmentBox(leaf_a, leaf_b, door.leaf_thickness, 0.01, door.height));
    const Point2 latch_edge = leaf_b;
    for (double side : {-1.0, 1.0}) {
      const double face = 0.5 * door.leaf_thickness;
      const Point2 rose = latch_edge - 0.07 * leaf_along + side * (face + 0.01) * leaf_normal;
      boxes.push_back({rose, std::atan2(leaf_along.y(), leaf_along.x()), 0.035, 0.01, 0.90, 1.06});
      const Point2 lever = latch_edge - 0.12 * leaf_along + side * (face + 0.05) * leaf_normal;
      boxes.push_back({lever, std::atan2(leaf_along.y(), leaf_along.x()), 0.07, 0.02, 0.95, 1.01});
    }
  }
  const SceneStairs& s = scene.stairs;
  const double yaw = std::atan2(s.ascending.y(), s.ascending.x());
  for (int k = 0; k + 1 < s.risers; ++k) {
    boxes.push_back({s.foot + (k + 0.5) * s.tread * s.ascending, yaw, 0.5 * s.tread, 0.5 * s.width,
                     0.0, (k + 1) * s.rise});
  }
  boxes.push_back({s.top() + 0.5 * s.block_length * s.ascending, yaw, 0.5 * s.block_length,
                   0.5 * s.width, 0.0, s.height()});
  return boxes;
}

StatusOr<grid::OccupancyGrid> RasterizeGroundFloor(const IndoorScene& scene, double resolution,
                                                   bool doors_as_set) {
  Terrain terrain = scene.ground;
  if (!doors_as_set) {
    for (Door& door : terrain.doors) door.open = true;
  }
  return RasterizeTerrain(terrain, resolution);
}

StatusOr<grid::OccupancyGrid> RasterizeUpperFloor(const IndoorScene& scene, double resolution) {
  StatusOr<grid::OccupancyGrid> raster = RasterizeTerrain(scene.upper, resolution);
  if (!raster.ok()) return raster;
  grid::OccupancyGrid grid = std::move(raster).value();
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const Point2 c = grid.CellCenter(x, y);
      const bool inside = c.x() > scene.hall_min.x() && c.x() < scene.hall_max.x() &&
                          c.y() > scene.hall_min.y() && c.y() < scene.hall_max.y();
      if (!inside) grid.at(x, y) = grid::kOccupiedValue;
    }
  }
  return grid;
}

}  // namespace fleetmap::sim
