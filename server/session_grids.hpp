#pragma once

#include <cstdint>
#include <vector>

#include "common/core/status.hpp"
#include "common/fusion/fusion_options.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "server/session_archive.hpp"

namespace fleetmap::server {

// Rasterizes each session's vector map onto the fleet's fused cell lattice and pads them all to
// the smallest box that holds every session, so the maps share size, resolution and origin (what
// the object learner needs). Cells a session never saw are unknown. The box holds at most
// options.max_grid_cells cells, and at most `max_cells` when it is positive: sessions too far
// apart for one grid are cut to the area most sessions mapped (fusion::ChooseGridWindow).
StatusOr<std::vector<grid::OccupancyGrid>> SessionGrids(const std::vector<MappingSession>& sessions,
                                                        const fusion::FusionOptions& options,
                                                        int64_t max_cells = 0);

}  // namespace fleetmap::server
