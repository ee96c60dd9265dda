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
// in `out_dir`. Returns the short summary printed at the end of `fleetmap sim`.
StatusOr<std::string> WriteFleetReport(const FleetSimOptions& options, const FleetRunResult& tiles,
                                       const std::optional<FleetRunResult>& compared,
                                       const grid::OccupancyGrid& truth,
                                       const std::string& out_dir);

// The fused grid (fleet frame) read at every cell centre of `truth`: same geometry as truth.
grid::OccupancyGrid ResampleOnto(const grid::OccupancyGrid& fused,
                                 const grid::OccupancyGrid& truth);

// The p-th percentile (0..100) of `values` by nearest rank; nullopt when empty.
std::optional<double> Percentile(std::vector<double> values, double p);

}  // namespace fleetmap::bench
