#include "server/session_grids.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "common/fusion/grid_window.hpp"
#include "common/fusion/tile_fusion.hpp"

namespace fleetmap::server {
namespace {

// One session on its own, its tiles within `window` only: a fusion of one robot is that robot's
// map on the fused lattice.
StatusOr<grid::OccupancyGrid> SessionGrid(const MappingSession& session,
                                          const fusion::TileRect& window,
                                          const fusion::FusionOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(fusion::TileFusion fusion, fusion::TileFusion::Create(options));
  for (const auto& [tile, map] : session.map.tiles) {
    if (!window.Contains(tile)) continue;
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
                                                        const fusion::FusionOptions& options,
                                                        int64_t max_cells) {
  // The tiles every session mapped, each with the sessions that mapped it.
  std::map<TileId, std::vector<int>> sessions_of;
  for (size_t i = 0; i < sessions.size(); ++i) {
    for (const auto& [tile, map] : sessions[i].map.tiles) {
      sessions_of[tile].push_back(static_cast<int>(i));
    }
  }
  if (sessions_of.empty()) return std::vector<grid::OccupancyGrid>(sessions.size());
  std::vector<fusion::SourcedTile> tiles;
  tiles.reserve(sessions_of.size());
  for (auto& [tile, mapped_by] : sessions_of) {
    // Sessions come oldest first: a tile appeared with the first session that mapped it.
    const auto first = static_cast<uint64_t>(mapped_by.front());
    tiles.push_back({tile, std::move(mapped_by), first});
  }
  // One window for all, within the grid budget: sessions kilometres apart (or a peer's tiles far
  // away) must not make every grid span the distance between them.
  const int cells = options.CellsPerTile();
  const int64_t grid_cells =
      max_cells > 0 ? std::min(max_cells, options.max_grid_cells) : options.max_grid_cells;
  const fusion::TileRect window =
      fusion::ChooseGridWindow(tiles, std::max<int64_t>(1, grid_cells / (int64_t{cells} * cells)))
          .rect;
  const double resolution = options.FusedResolution();
  const Pose2 origin{window.min.x * options.tile_size, window.min.y * options.tile_size, 0.0};
  std::vector<grid::OccupancyGrid> padded;
  for (const MappingSession& session : sessions) {
    FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid grid,
                              SessionGrid(session, window, options));
    grid::OccupancyGrid out(static_cast<int>(window.width() * cells),
                            static_cast<int>(window.height() * cells), resolution, origin);
    if (!grid.empty()) {
      // Every grid's origin is a tile corner on one lattice: whole cells apart.
      const int x0 = static_cast<int>(std::lround((grid.origin().x - origin.x) / resolution));
      const int y0 = static_cast<int>(std::lround((grid.origin().y - origin.y) / resolution));
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
