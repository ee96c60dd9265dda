#pragma once

#include <optional>
#include <string>

#include "bench/fleet/fleet_sim.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::bench {

// A fleet run on the tile wire summed up against the ground truth and the grid-wire baselines
// its agents measured (baseline_bytes.hpp) and, if it ran, the same scenario on a grid wire for
// real (`compared`): report.md, report.json and fused.png (the fused map with the robots' paths)
// in `out_dir`. With robots at unknown poses (options.sim_frames) it also reports how each robot
// was placed (placement.csv too) and, if given, the same scenario with known poses
// (`known_poses`). Returns the short summary printed at the end of `fleetmap sim`.
StatusOr<std::string> WriteFleetReport(const FleetSimOptions& options, const FleetRunResult& tiles,
                                       const std::optional<FleetRunResult>& compared,
                                       const grid::OccupancyGrid& truth, const std::string& out_dir,
                                       const std::optional<FleetRunResult>& known_poses = {});

// The fused grid read at every cell centre of `truth` (same geometry as truth);
// `fleet_from_world` takes the truth's frame to the fused map's.
grid::OccupancyGrid ResampleOnto(const grid::OccupancyGrid& fused, const grid::OccupancyGrid& truth,
                                 const Transform2& fleet_from_world = Transform2::Identity());

// How far a robot's placement is from the truth: at the centroid of its known cells, the distance
// between where the placement and the truth put it (cells of `resolution`), and the yaw error.
struct PlacementError {
  double cells = 0.0;
  double yaw_deg = 0.0;
};
// nullopt when the robot was never placed or had no known cells; `world_from_anchor` is the
// anchor's true world_from_map (the fleet frame in the terrain's).
std::optional<PlacementError> PlacementErrorOf(const RobotPlacement& placement,
                                               const Pose2& world_from_anchor, double resolution);

// The p-th percentile (0..100) of `values` by nearest rank; nullopt when empty.
std::optional<double> Percentile(std::vector<double> values, double p);

}  // namespace fleetmap::bench
