#include "server/session_grids.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/fusion/tile_fusion.hpp"

namespace fleetmap::server {
namespace {

// One session on its own: a fusion of one robot is that robot's map on the fused lattice.
StatusOr<grid::OccupancyGrid> SessionGrid(const MappingSession& session,
                                          const fusion::FusionOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(fusion::TileFusion fusion, fusion::TileFusion::Create(options));
  for (const auto& [tile, map] : session.map.tiles) {
    FLEETMAP_RETURN_IF_ERROR(fusion.UpdateRobotTile(session.robot, tile, map, session.ended)
                                 .WithContext("session " + std::to_string(session.id)));
  }
  // Fusing also re-vectorizes the tiles, which is not needed here, but it is what rasterizes them
  // onto the fused cells.
  FLEETMAP_RETURN_IF_ERROR(fusion.FuseChanged().status());
  return fusion.FusedGrid();
}

}  // namespace

StatusOr<std::vector<grid::OccupancyGrid>> SessionGrids(const std::vector<MappingSession>& sessions,
                                                        const fusion::FusionOptions& options) {
  std::vector<grid::OccupancyGrid> grids;
  for (const MappingSession& session : sessions) {
    FLEETMAP_ASSIGN_OR_RETURN(grid::OccupancyGrid grid, SessionGrid(session, options));
    grids.push_back(std::move(grid));
  }
  // Every grid's origin is a tile corner on one lattice: whole cells apart.
  const double resolution = options.FusedResolution();
  double min_x = INFINITY, min_y = INFINITY, max_x = -INFINITY, max_y = -INFINITY;
  for (const grid::OccupancyGrid& grid : grids) {
    if (grid.empty()) continue;
    min_x = std::min(min_x, grid.origin().x);
    min_y = std::min(min_y, grid.origin().y);
    max_x = std::max(max_x, grid.origin().x + grid.width() * resolution);
    max_y = std::max(max_y, grid.origin().y + grid.height() * resolution);
  }
  if (!std::isfinite(min_x)) return grids;  // nothing mapped at all
  const int width = static_cast<int>(std::lround((max_x - min_x) / resolution));
  const int height = static_cast<int>(std::lround((max_y - min_y) / resolution));
  std::vector<grid::OccupancyGrid> padded;
  for (const grid::OccupancyGrid& grid : grids) {
    grid::OccupancyGrid out(width, height, resolution, Pose2{min_x, min_y, 0.0});
    if (!grid.empty()) {
      const int x0 = static_cast<int>(std::lround((grid.origin().x - min_x) / resolution));
      const int y0 = static_cast<int>(std::lround((grid.origin().y - min_y) / resolution));
      for (int y = 0; y < grid.height(); ++y) {
        std::memcpy(&out.at(x0, y0 + y), grid.data().data() + static_cast<size_t>(y) * grid.width(),
                    static_cast<size_t>(grid.width()));
      }
    }
    padded.push_back(std::move(out));
  }
  return padded;
}

}  // namespace fleetmap::server
