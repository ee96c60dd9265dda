#pragma once

// Finds closed doors in a 3D point cloud (ALGORITHMS.md 3, quasi-static entities): voxel filter,
// RANSAC for vertical planes, and in each plane's 2D image (s along the plane, z up) the connected
// patches, cut into runs of densely filled columns, whose four corners sit at the floor and at a
// door's height, whose width matches a door and which have a wall beside both
// edges. The rotation axis is on the side opposite the
// handle: the points just off the plane near handle height are counted on both sides, and the side
// with more of them is the latch side.
//
// The opening direction is the plane normal pointing away from `viewpoint` (the sensor), i.e. into
// the side the robot cannot see; without a viewpoint it is left zero, and the extrapolator orients
// the door from the local map (InferOpeningDirection in map_queries.hpp).
//
// Thread-safety: stateless.

#include <optional>
#include <vector>

#include "common/extrapolation/point_cloud.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::extrapolation {

struct DoorDetectorOptions {
  double voxel_size = 0.03;
  double plane_threshold = 0.015;  // m
  double max_tilt_error = 0.17;    // radians from vertical
  int max_planes = 16;
  int min_plane_points = 150;
  double image_cell = 0.05;  // m, the plane's 2D image
  double min_width = 0.6;    // door width range, m
  double max_width = 1.4;
  // Door leaf height range (m). Standard leaves are 1.98-2.1 m; a lower bound near that keeps out
  // wall strips whose top the camera's field of view cuts.
  double min_height = 1.95;
  double max_height = 2.3;
  double floor_tolerance = 0.15;  // the leaf's bottom corners within this of the floor, m
  double min_fill = 0.75;         // fraction of the leaf's rectangle the patch covers
  // A corner is found if the patch has a point this close to it (m): the jambs and the lintel
  // hide a strip of the leaf's edge when the door is seen at an angle.
  double corner_tolerance = 0.15;
  // Handle search: points this far in front of the leaf (m) ...
  double handle_min_offset = 0.025;
  double handle_max_offset = 0.15;
  // ... at these heights (m), within this of each vertical edge (m).
  double handle_min_z = 0.8;
  double handle_max_z = 1.25;
  double handle_edge_band = 0.25;
  // The wall around the door: at least this many points within wall_max_offset of the leaf's
  // plane, within wall_search beside each vertical edge (0 turns the check off).
  int min_wall_points = 20;
  double wall_max_offset = 0.15;
  double wall_search = 0.4;
  int iterations = 300;
  uint32_t seed = 11;
};

struct DetectedDoor {
  scene::DoorEntity entity;
  double height = 0;  // m, top of the leaf
  int handle_points_latch = 0;
  int handle_points_hinge = 0;
};

// Ids are "door_<k>" in detection order. `viewpoint` (map frame, 2D) orients the doors.
std::vector<DetectedDoor> DetectDoors(const PointCloud& cloud,
                                      const std::optional<Point2>& viewpoint,
                                      const DoorDetectorOptions& options = {});

}  // namespace fleetmap::extrapolation
