#pragma once

// Series of maps of one real floor with furniture drawn in and moved between them, for the
// object-learning benchmark on real building maps (issue 22). Floor-plan data sets draw furniture
// as filled shapes in free space; this does the same on a shared map_server map: the floor is
// cropped (or padded with unknown) to a fixed size around its most free window, then every map of
// the series gets the same pieces (rectangles, L-shapes, small discs) at new random poses (yaw a
// multiple of 90 degrees, as furniture stands along walls), each with a gap of free floor around
// it, but for rows of desks standing one cell apart. A piece is kept away from where any piece
// stood in the earlier maps when the floor allows it, and else from where pieces stood in all
// other maps but one, so every cell of every piece is a difference (free in some other map).
// Same seed, same series.
//
// Thread-safety: stateless.

#include <cstdint>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

// The shapes drawn, in the order piece i gets shape i % kPlanShapeCount.
enum class PlanShape : int { kDesk, kCabinet, kTable, kLShape, kBin, kSmallBin };
inline constexpr int kPlanShapeCount = 6;
const char* PlanShapeName(PlanShape shape);

struct RealPlanOptions {
  int width = 800;   // cells of every map (the floor is cropped or padded), >= 16
  int height = 544;  // cells, >= 16
  int maps = 4;      // >= 2
  int pieces = 40;   // per map, >= 1
  double gap = 0.3;  // metres of free floor around each piece (and between pieces), >= 0
  // Rows of 4 desks end to end, one free cell (5 cm) apart, as offices place them: region
  // growing joins them into one changed region of 4.8 m that the learner has to split. The
  // first 4 * rows pieces are the rows' desks.
  int rows = 2;  // >= 0
  uint32_t seed = 1;
};

struct PlacedPiece {
  int piece = 0;  // the same physical piece in every map
  PlanShape shape = PlanShape::kDesk;
  Point2 centre = Point2::Zero();  // map frame, metres: centroid of the drawn cells
  double yaw = 0.0;
  int cells = 0;  // cells drawn
};

struct RealPlanSeries {
  std::string floor;  // the source map's path
  std::vector<grid::OccupancyGrid> maps;
  std::vector<std::vector<PlacedPiece>> pieces;  // per map, the pieces it shows
  int unplaced = 0;             // pieces that found no free spot in some map (not drawn there)
  int overlapping_earlier = 0;  // pieces placed over an earlier map's piece (floor too full)
};

// Errors: the floor map cannot be read (the message names it), options out of range.
StatusOr<RealPlanSeries> MakeRealPlanSeries(const std::string& floor_yaml,
                                            const RealPlanOptions& options);

// The same from a grid already loaded (tests).
StatusOr<RealPlanSeries> MakeRealPlanSeries(const grid::OccupancyGrid& floor,
                                            const RealPlanOptions& options);

}  // namespace fleetmap::bench
