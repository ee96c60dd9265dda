#pragma once

// Builds the route graph of an occupancy grid (the fused map) and keeps it current: Build() makes
// it from a whole grid, Update() after some cells changed recomputes only a window around them
// and stitches it to the rest. Ids are kept across builds for every node whose position and every
// edge whose two nodes did not change (a fleet manager keys tasks on them); new ones get fresh ids.
//
// The method (docs/route-graph.md): the distance transform of free space (unknown cells are not
// free); the cells where the robot fits with its margin; their homotopic skeleton (Skeleton);
// its curves between junctions and dead ends, spurs pruned and near junctions merged; each curve
// cut at doorways (the narrowest point between two wider spaces) and tile borders, then
// straightened into segments proven to keep the clearance, long ones cut into lanes.
//
// Thread-safety: one thread uses a builder; the graphs it returns are values.

#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/grid/cell_rect.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/route_graph/clearance_map.hpp"
#include "common/route_graph/route_graph.hpp"
#include "common/route_graph/route_overlay.hpp"
#include "common/route_graph/segment_memo.hpp"
#include "common/route_graph/skeleton.hpp"
#include "common/scene/submap_graph.hpp"

namespace fleetmap::route_graph {

struct RouteGraphOptions {
  double robot_radius = 0.3;  // metres
  // Nodes keep radius + margin from every non-free cell, edges radius + margin - one cell (the
  // grid's discretisation); the margin used is at least one cell, so edges always keep the radius.
  double clearance_margin = 0.05;
  double lane_spacing = 5.0;     // a straight edge longer than this is cut into equal lanes
  double merge_distance = 1.5;   // junctions closer than this along a corridor become one
  double min_spur_length = 1.5;  // dead ends shorter than this (beyond a wall's bump) are noise
  double doorway_ratio = 0.6;    // a clearance minimum below this share of both sides' is a door
  double doorway_window = 2.0;   // metres looked at on each side of a doorway candidate
  // Clearances are exact up to this, metres, and at least a metre past radius + margin (a large
  // robot raises it: ExactClearanceUpTo()).
  double clearance_cap = 3.0;
  double tile_size = 20.0;  // curves are cut at these tile borders, so changes stay local
  // Nodes this close that see each other get a straight edge when the graph's way round is more
  // than `shortcut_ratio` times longer (0: none).
  double shortcut_radius = 6.0;
  double shortcut_ratio = 1.05;
  // Parts of the graph a robot moves less than this in (edge length plus the widest circle its
  // centre moves in at a node) are dropped: pockets of free space going nowhere.
  double min_part_length = 1.0;
  // Nodes joined by an edge shorter than this become one (0: the robot's diameter: a robot on
  // one node covers the other, and a fleet manager gains nothing from both).
  double min_node_distance = 0.0;
  std::string frame = "map";
  grid::StateThresholds thresholds;

  // The clearance the distance transform computes exactly: clearance_cap, or a metre past what
  // the robot needs when that is more.
  double ExactClearanceUpTo() const;
  // min_node_distance, or the robot's diameter when it is 0.
  double MinNodeDistance() const;
  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// What a graph is built from beside the grid; each part optional.
struct MapContext {
  // Observed sub-maps (rooms) in the grid's frame: each room gets a room-centre node.
  const scene::SubmapGraph* rooms = nullptr;
  // Predicted free space and learned movable objects on the grid's cells: the robot may plan
  // through them, and the nodes and edges on them are marked (RouteNode::predicted,
  // RouteEdge::predicted, RouteEdge::blocking_object).
  const RouteOverlay* overlay = nullptr;
};

class RouteGraphBuilder {
 public:
  // `options` must be valid (Validate()).
  explicit RouteGraphBuilder(RouteGraphOptions options);

  // The graph of `grid` (yaw 0; kInvalidArgument otherwise, or for an empty grid) and its
  // context (rooms, overlay: on `grid`'s cells). Ids carry over from the previous graph where the
  // geometry is the same.
  StatusOr<RouteGraph> Build(const grid::OccupancyGrid& grid, const MapContext& context = {});

  // The graph after the cells in `changed` (rectangles of the grid, e.g. changed tiles) changed:
  // `grid` has the geometry of the last Build. Only a window around the cells of `changed` whose
  // state (free or not) differs from the last build's is recomputed, and around the cells whose
  // overlay differs from the last one's; none, and the graph is the same, ids and all. The
  // context is this update's (no rooms: no room centres).
  // kInvalidArgument before any Build or for a grid of another geometry.
  StatusOr<RouteGraph> Update(const grid::OccupancyGrid& grid,
                              const std::vector<grid::CellRect>& changed,
                              const MapContext& context = {});

  const RouteGraphOptions& options() const { return options_; }
  // The clearances of the last build (for checks and planners on the same grid).
  const ClearanceMap& clearance() const { return clearance_; }
  // The clearance a node needs (radius + margin) and an edge keeps everywhere, on this grid.
  double NodeClearance() const;
  double EdgeClearance() const;

 private:
  RouteGraph Extract();
  // The observed rooms' most open cells that give a node the clearance it needs.
  void FindRoomCentres(const scene::SubmapGraph* rooms);
  // Marks the nodes and edges on the overlay's cells (edges' ends are node indices still).
  void MarkOverlay(RouteGraph* graph) const;
  void AssignIds(RouteGraph* graph);

  RouteGraphOptions options_;
  double resolution_ = 0.0;
  Point2 origin_ = Point2::Zero();
  // Per cell of the last grid built from: 1 where free. What Update compares with.
  std::vector<uint8_t> free_;
  ClearanceMap clearance_;
  // Segment checks on clearance_ kept across updates (what an update re-traces far from its
  // window is looked up, not walked again).
  SegmentMemo segment_memo_;
  Skeleton skeleton_;
  std::vector<Point2> room_centres_;
  RouteOverlay overlay_;  // of the last build or update
  std::optional<RouteGraph> previous_;
  uint32_t next_id_ = 0;
};

}  // namespace fleetmap::route_graph
