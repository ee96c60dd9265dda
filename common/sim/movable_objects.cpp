#include "common/sim/movable_objects.hpp"

#include <cmath>
#include <numbers>

namespace fleetmap::sim {
namespace {

// Shape outlines in the object frame, centred on the bounding disc's centre.
std::vector<Point2> Outline(MovableShape shape) {
  switch (shape) {
    case MovableShape::kChair: {
      // An L: arms of 0.55 m, 0.15 m thick, the corner at (-0.275, -0.275).
      const double a = 0.275, t = 0.15;
      return {{-a, -a}, {a, -a}, {a, -a + t}, {-a + t, -a + t}, {-a + t, a}, {-a, a}};
    }
    case MovableShape::kBin: {
      std::vector<Point2> points;
      constexpr int kSides = 20;
      for (int i = 0; i < kSides; ++i) {
        const double phi = 2.0 * std::numbers::pi * i / kSides;
        points.emplace_back(0.2 * std::cos(phi), 0.2 * std::sin(phi));
      }
      return points;
    }
    case MovableShape::kBox:
      return {{-0.35, -0.2}, {0.35, -0.2}, {0.35, 0.2}, {-0.35, 0.2}};
  }
  return {};
}

}  // namespace

std::string_view MovableShapeName(MovableShape shape) {
  switch (shape) {
    case MovableShape::kChair:
      return "chair";
    case MovableShape::kBin:
      return "bin";
    case MovableShape::kBox:
      return "box";
  }
  return "unknown";
}

std::optional<MovableShape> MovableShapeFromName(std::string_view name) {
  for (MovableShape shape : {MovableShape::kChair, MovableShape::kBin, MovableShape::kBox}) {
    if (MovableShapeName(shape) == name) return shape;
  }
  return std::nullopt;
}

double MovableShapeRadius(MovableShape shape) {
  double radius = 0.0;
  for (const Point2& p : Outline(shape)) radius = std::max(radius, p.norm());
  return radius;
}

SolidPolygon MovableObjectPolygon(const MovableObject& object) {
  SolidPolygon polygon;
  polygon.kind = ObstacleKind::kFurniture;
  polygon.movable = true;
  const Transform2 map_from_object = object.pose.ToTransform();
  for (const Point2& p : Outline(object.shape)) polygon.points.push_back(map_from_object * p);
  return polygon;
}

Terrain WithMovableObjects(const Terrain& base, const std::vector<MovableObject>& objects) {
  Terrain terrain = base;
  for (const MovableObject& object : objects) {
    terrain.polygons.push_back(MovableObjectPolygon(object));
  }
  return terrain;
}

}  // namespace fleetmap::sim
