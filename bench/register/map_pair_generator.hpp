#pragma once

// Pairs of robot maps made from one complete map, for the registration benchmark (issue 18,
// deliverable 5) and the calibration of Registration::confidence: two exploration-like crops
// (the known cells within a geodesic reach of a random free start), with ragged frontiers and a
// few noise specks, at a requested overlap; B is then turned into a frame of its own, and the
// truth a_from_b is kept.
//
// Pure functions of their inputs and the generator they are given: any thread may call them.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

struct MapPairOptions {
  // Each crop holds a random share in [min_crop_share, max_crop_share] of the source's known
  // cells (measured before the frontier is made ragged).
  double min_crop_share = 0.4;
  double max_crop_share = 0.7;
  // A pair is kept when its overlap (share of B's known cells also known in A) is within this of
  // the requested one; at most max_attempts crops of B are tried for one A.
  double overlap_tolerance = 0.05;
  int max_attempts = 40;
  // Ragged frontier: the crop's border moves in and out by up to this many cells, following a
  // smooth random field whose features are about frontier_wavelength_cells across.
  double frontier_amplitude_cells = 4.0;
  double frontier_wavelength_cells = 12.0;
  // Isolated noise cells (occupied or free, at random) sprinkled over each crop's bounding box.
  int min_specks = 3;
  int max_specks = 12;
  // Independent SLAM noise on each robot's map (issue 31): two SLAM runs rasterize the same wall a
  // cell apart here and there, while two crops of one map share every wall cell. Each wall face
  // cell (an occupied cell beside a free one) moves by one cell with this probability, drawn for
  // A and B apart: half of the moves advance the face into the free cell beside it, half recede
  // it (the face cell turns free where the wall behind it stays closed). 0: crops share walls.
  double wall_noise = 0.0;
  // B's frame: its origin lies up to this far (metres) from A's, with any yaw.
  double max_origin_offset = 500.0;
  // > 1: B also as the robot saw it after 1 / growth_steps, 2 / growth_steps, ... of its drive
  // (MapPair::b_growing), for the sequential test on growing maps.
  int growth_steps = 0;
};

struct MapPair {
  grid::OccupancyGrid a;  // in the source map's frame (cropped: another origin, same frame)
  grid::OccupancyGrid b;  // in a frame of its own
  Transform2 a_from_b = Transform2::Identity();  // the truth: p_a = a_from_b * p_b
  double overlap = 0.0;  // achieved: share of B's known cells also known in A
  double yaw_b = 0.0;    // how far B's cells were turned (radians)
  // With MapPairOptions::growth_steps > 1: B after k / growth_steps of its drive, k = 1 ..
  // growth_steps - 1, in B's frame (the same a_from_b), each with a ragged frontier of its own;
  // B itself is the last step.
  std::vector<grid::OccupancyGrid> b_growing;
};

// One pair from `source` at `target_overlap` (in (0, 1)). kNotFound when no crop within the
// tolerance was found in max_attempts tries (the caller may try again with another draw);
// kInvalidArgument when the source has too few free cells to crop.
StatusOr<MapPair> MakeMapPair(const grid::OccupancyGrid& source, double target_overlap,
                              const MapPairOptions& options, std::mt19937& rng);

// `map` seen by another robot: its cells turned by `yaw` about the grid's centre
// (nearest-neighbour resampling, as a second SLAM run would rasterize the same walls), in a frame
// whose origin is `origin`. `*map_from_turned` takes the new map's frame to `map`'s frame.
grid::OccupancyGrid TurnIntoNewFrame(const grid::OccupancyGrid& map, double yaw,
                                     const Pose2& origin, Transform2* map_from_turned);

// How B drifts against A (issue 31): a smooth warp of B's cells about a pivot, as a second SLAM
// run's scale error and slow heading drift would bend the same walls. Each drifted pair draws
// its scale uniformly in [-max_scale, max_scale] and its bend in
// [-max_bend_deg_per_m, max_bend_deg_per_m].
struct DriftOptions {
  double max_scale = 0.02;          // 2 cm per metre from the pivot
  double max_bend_deg_per_m = 0.1;  // heading turns this much per metre along B's x axis
};

// `map` warped about `pivot` (map frame): a point at d = p - pivot moves to
// pivot + (1 + scale) R(bend_per_metre * d.x) d, d.x along the grid's x axis; nearest-neighbour
// resampling onto a grid grown by a margin that holds the warped cells, in the same map frame.
// The pivot and the direction of the map frame at the pivot do not move, so a truth a_from_b
// still holds there.
grid::OccupancyGrid Warp(const grid::OccupancyGrid& map, const Point2& pivot, double scale,
                         double bend_per_metre);

// Where Warp(map, pivot, scale, bend_per_metre) takes the map-frame point `p`, and how far it
// turns the map there (radians).
struct WarpedPoint {
  Point2 point;
  double turn = 0.0;
};
WarpedPoint WarpPoint(const grid::OccupancyGrid& map, const Point2& pivot, double scale,
                      double bend_per_metre, const Point2& p);

// The map-frame centroid of the pair's overlap: B's known cells that the truth lays on A's known
// cells (B's known centroid when there are none).
Point2 OverlapCentroid(const MapPair& pair);

// The cells [x0, x0 + w) x [y0, y0 + h) of `map` in `map`'s frame (origin at the crop's corner);
// cells outside `map` are unknown.
grid::OccupancyGrid CropCells(const grid::OccupancyGrid& map, int x0, int y0, int w, int h);

// The map-frame centroid of a map's known cells ((0, 0) when it has none).
Point2 KnownCentroid(const grid::OccupancyGrid& map);

}  // namespace fleetmap::bench
