#include "common/extrapolation/building_outline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/extrapolation/extrapolator.hpp"
#include "common/extrapolation/predicted_free_grid.hpp"
#include "tests/unit/extrapolation/test_maps.hpp"

namespace fleetmap::extrapolation {
namespace {

using testing::kRes;

// A building's edge, in building coordinates (metres): a corridor y in [0.3, 1.8] from x = 0.3 to
// 12.4 (walls all round it, its east end wall seen), rooms north of it (y in [2.0, 3.2]) behind a
// 0.2 m wall, the building's outer wall y in [3.2, 3.6], outside beyond. Room A (x in [0.3, 4.0])
// was explored: its floor, its walls and the outer wall's face are seen. Room B (x in [4.2, 8.0])
// nobody entered. Room C (x in [8.2, 12.0]) is the hidden one, behind a closed door at
// x in [9.5, 10.7] (1.2 m) on the corridor's face. The nearest the robot saw of the outer wall
// is 4.2 m from C, beyond what the door's own clipping (DoorSpace) looks at. The map is drawn at
// `yaw` (radians) to the grid, around the point (1, 1): the building lies at an angle to the grid.
struct Edge {
  grid::OccupancyGrid map;
  scene::DoorEntity door;
  Eigen::Isometry2d map_from_building;
};

Edge BuildingEdge(double yaw) {
  Edge edge;
  edge.map_from_building =
      Eigen::Translation2d(1.0, 1.0) * Eigen::Rotation2Dd(yaw) * Eigen::Translation2d(2.0, 2.0);
  const Eigen::Isometry2d building_from_map = edge.map_from_building.inverse();
  edge.map = grid::OccupancyGrid(400, 400, kRes);
  const auto in = [](const Point2& p, double x0, double y0, double x1, double y1) {
    return p.x() >= x0 && p.x() < x1 && p.y() >= y0 && p.y() < y1;
  };
  for (int y = 0; y < edge.map.height(); ++y) {
    for (int x = 0; x < edge.map.width(); ++x) {
      const Point2 p = building_from_map * edge.map.CellCenter(x, y);
      int8_t value = grid::kUnknownValue;
      // Seen walls: the corridor's (all round it, 0.1 m of each), room A's, the outer wall's face
      // above A.
      if (in(p, 0.2, 0.2, 12.5, 1.9)) value = grid::kOccupiedValue;
      if (in(p, 0.2, 1.9, 4.1, 3.3)) value = grid::kOccupiedValue;
      if (in(p, 0.3, 0.3, 12.4, 1.8)) value = grid::kFreeValue;  // corridor
      if (in(p, 0.3, 2.0, 4.0, 3.2)) value = grid::kFreeValue;   // room A
      if (in(p, 1.5, 1.8, 2.4, 2.0)) value = grid::kFreeValue;   // room A's open doorway
      edge.map.at(x, y) = value;
    }
  }
  edge.door.id = "door_c";
  edge.door.hinge = edge.map_from_building * Point2(9.5, 1.8);
  edge.door.latch = edge.map_from_building * Point2(10.7, 1.8);
  edge.door.opening_direction = edge.map_from_building.linear() * Vector2(0, 1);
  return edge;
}

// The door's predicted cells, in building coordinates.
std::vector<Point2> PredictedCells(const Edge& edge, bool building_outline, double p_th) {
  scene::Entities entities;
  entities.doors.push_back(edge.door);
  ExtrapolationOptions options;
  options.p_th = p_th;
  options.door_building_outline = building_outline;
  const auto result = Extrapolate(edge.map, entities, options);
  EXPECT_TRUE(result.ok());
  std::vector<Point2> cells;
  if (!result.ok()) return cells;
  const Eigen::Isometry2d building_from_map = edge.map_from_building.inverse();
  for (const scene::Submap& s : result->graph.submaps) {
    if (s.kind != scene::SubmapKind::kPredictedDoor) continue;
    const grid::OccupancyGrid in_map = SubmapGridInMapFrame(s);
    for (int y = 0; y < in_map.height(); ++y) {
      for (int x = 0; x < in_map.width(); ++x) {
        if (in_map.StateAt(x, y) == grid::CellState::kFree) {
          cells.push_back(building_from_map * in_map.CellCenter(x, y));
        }
      }
    }
  }
  return cells;
}

TEST(BuildingOutlineTest, FindsTheBuildingsPrincipalDirection) {
  for (const double degrees : {0.0, 17.0, 30.0, 62.0}) {
    const Edge edge = BuildingEdge(degrees * std::numbers::pi / 180.0);
    const BuildingOutline outline(edge.map, {});
    double found = outline.principal_angle() * 180.0 / std::numbers::pi;
    const double expected = std::fmod(degrees, 90.0);
    // Modulo 90 degrees, either side of 0.
    double error = std::fmod(std::abs(found - expected), 90.0);
    error = std::min(error, 90.0 - error);
    EXPECT_LT(error, 1.5) << "drawn at " << degrees << " deg, found " << found;
    EXPECT_GE(outline.outer_walls(), 1) << degrees;
  }
}

// The room at the building's edge: its prediction stops at the continuation of the outer wall seen
// above room A, 4.2 m away, and still covers the room.
TEST(BuildingOutlineTest, EdgeRoomsPredictionStopsAtTheOuterWallsContinuation) {
  for (const double degrees : {0.0, 30.0}) {
    const Edge edge = BuildingEdge(degrees * std::numbers::pi / 180.0);
    const double cell_area = kRes * kRes;
    // Half a cell's diagonal: a cell centre on the wall's face line may sit that far past it.
    const double slack = 0.75 * kRes;
    const std::vector<Point2> bounded = PredictedCells(edge, true, 0.5);
    int64_t in_room = 0;
    for (const Point2& p : bounded) {
      EXPECT_LT(p.y(), 3.2 + slack) << "at " << degrees << " deg: " << p.transpose();
      in_room += p.x() > 8.2 && p.x() < 12.0 && p.y() > 2.0 && p.y() < 3.2;
    }
    EXPECT_GT(in_room * cell_area, 2.0) << degrees;
    // Without the outline, the same door's prediction runs out of the building: the test can fail.
    int64_t outside = 0;
    for (const Point2& p : PredictedCells(edge, false, 0.5)) outside += p.y() > 3.2 + slack;
    EXPECT_GT(outside * cell_area, 0.2) << degrees;
  }
}

// The door's own wall is never an outline: a door in the building's outermost observed wall (the
// corridor's south wall, nothing seen behind it) still predicts the space it opens onto.
TEST(BuildingOutlineTest, ADoorInAnOuterWallStillPredicts) {
  Edge edge = BuildingEdge(0.0);
  edge.door.hinge = edge.map_from_building * Point2(5.0, 0.3);
  edge.door.latch = edge.map_from_building * Point2(5.9, 0.3);
  edge.door.opening_direction = Vector2(0, -1);
  const BuildingOutline outline(edge.map, {});
  const std::vector<uint8_t> allowed = outline.AllowedFor(edge.door, Vector2(0, -1));
  const std::optional<grid::CellIndex> below =
      edge.map.CellAt(edge.map_from_building * Point2(5.45, -0.5));
  ASSERT_TRUE(below.has_value());
  EXPECT_EQ(allowed[static_cast<size_t>(below->y) * edge.map.width() + below->x], 1);
  // The same cell for room C's door is outside the outline (beyond the corridor's south wall).
  const BuildingOutline same(edge.map, {});
  const Vector2 north = edge.map_from_building.linear() * Vector2(0, 1);
  const std::vector<uint8_t> for_c = same.AllowedFor(BuildingEdge(0.0).door, north);
  EXPECT_EQ(for_c[static_cast<size_t>(below->y) * edge.map.width() + below->x], 0);
}

}  // namespace
}  // namespace fleetmap::extrapolation
