#pragma once

// Rooms and doorways found in a real occupancy map (a SLAM map in ROS map_server format), for the
// closed-door benchmark on real maps (docs/extrapolation.md, "Benchmark on real maps"). The same
// rules for every map, nothing tuned per map:
//   1. clearance: each free cell's distance to the nearest cell that is not free (occupied or
//      unknown), by a two-pass chamfer transform;
//   2. room cores: the free cells with a clearance above `core_clearance` (the free space eroded,
//      which cuts every passage narrower than about twice that), in 4-connected components, the
//      ones smaller than `min_core_area` dropped (furniture gaps and scan noise);
//   3. rooms: the cores grown back through the free space (4-connected, breadth first, so each
//      free cell joins the core it is closest to along the free space);
//   4. doorways: where two grown rooms touch, the touching cells of one side make a doorway when
//      they span `min_door_width` to `max_door_width` (their extent along their principal axis).
// A room is kept as a scene when its area is in [min_room_area, max_room_area] and it touches
// exactly one other room, through a doorway.
//
// `SegmentBuilding` says which cells are in the building: the known cells (free or occupied)
// closed by a disc of `building_closing` radius, their holes filled; an unknown cell the grid's
// edge reaches without crossing that set is outside. A scan that stopped short of a wall leaves
// unknown cells inside (no truth there); space beyond the outer walls is outside.
//
// `PlanForRoom` turns one kept room into a `FloorPlan` (floor_plan.hpp) cropped around it, so the
// floor-plan experiment's `HideRoom` and scoring run unchanged on it: the room is room 0, all
// other free space is the corridor, occupied cells are walls, unknown cells are kPlanUnknown
// inside the building (hidden as outside is, but with no ground truth: a prediction there is not
// scored) and kPlanUnknownOutside outside it (no building there: strictly, a prediction there is
// wrong), and the
// door's leaf is the row of cells on the far side of the doorway.
//
// Thread-safety: stateless.

#include <cstdint>
#include <vector>

#include "bench/extrapolation/floor_plan.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

struct RoomSegmentationOptions {
  double core_clearance = 0.6;  // metres: cuts passages up to ~1.2 m wide
  double min_core_area = 0.5;   // m2
  double min_door_width = 0.6;  // metres
  double max_door_width = 1.3;
  double min_room_area = 4.0;  // m2
  double max_room_area = 80.0;
  double crop_margin = 6.0;  // metres of map kept around a room's bounding box
  // Metres: gaps in the known space narrower than twice this are inside the building (a scan's
  // shadow behind furniture, a doorway nobody looked through).
  double building_closing = 1.0;
};

struct SegmentedDoorway {
  int32_t room = 0;                // the room behind the door
  int32_t other = 0;               // the room it opens onto
  std::vector<size_t> leaf_cells;  // `other`'s cells touching `room` (row-major)
  Point2 jamb_a = Point2::Zero();
  Point2 jamb_b = Point2::Zero();
  Vector2 into_room = Vector2::Zero();
  double width = 0.0;
};

struct RoomSegmentation {
  std::vector<int32_t> labels;    // per cell (row-major): a room index, or -1 (not free, no room)
  std::vector<double> room_area;  // m2, per room
  std::vector<std::vector<int32_t>> neighbours;  // per room, the rooms it touches
  std::vector<SegmentedDoorway> doorways;        // kept rooms only, one each, in room order
};

RoomSegmentation SegmentRooms(const grid::OccupancyGrid& map,
                              const RoomSegmentationOptions& options);

// Per cell (row-major): 1 inside the building, 0 outside (above).
std::vector<uint8_t> SegmentBuilding(const grid::OccupancyGrid& map, double closing_radius);

// The kept room of `doorway` as a one-door floor plan, cropped to its bounding box plus
// `options.crop_margin`. `building` (SegmentBuilding of `map`, or empty: all inside) splits the
// unknown cells into kPlanUnknown and kPlanUnknownOutside.
FloorPlan PlanForRoom(const grid::OccupancyGrid& map, const RoomSegmentation& segmentation,
                      const SegmentedDoorway& doorway, const RoomSegmentationOptions& options,
                      const std::vector<uint8_t>& building = {});

}  // namespace fleetmap::bench
