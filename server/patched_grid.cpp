#include "server/patched_grid.hpp"

#include <algorithm>

namespace fleetmap::server {

void PatchedGrid::Replace(transport::MapMessage map) {
  whole_map_stamp_ = map.stamp;
  map_ = std::move(map);
}

StatusOr<PatchedGrid::Outcome> PatchedGrid::Judge(Timestamp update_stamp) const {
  if (!map_) {
    return InvalidArgumentError(
        "a map update came before any whole map on the robot's map topic: nothing to patch");
  }
  return update_stamp < whole_map_stamp_ ? Outcome::kStale : Outcome::kApplied;
}

StatusOr<PatchedGrid::Outcome> PatchedGrid::Apply(const transport::MapUpdate& update) {
  FLEETMAP_ASSIGN_OR_RETURN(const Outcome outcome, Judge(update.stamp));
  if (outcome == Outcome::kStale) return outcome;
  FLEETMAP_RETURN_IF_ERROR(transport::ApplyMapUpdate(update, &map_->grid));
  map_->stamp = std::max(map_->stamp, update.stamp);
  return outcome;
}

StatusOr<PatchedGrid::Outcome> PatchedGrid::Apply(const transport::CompressedMapUpdate& update) {
  FLEETMAP_ASSIGN_OR_RETURN(const Outcome outcome, Judge(update.stamp));
  if (outcome == Outcome::kStale) return outcome;
  const grid::OccupancyGrid& grid = map_->grid;
  // The rectangle first: raw_size must then be its cells, so nothing beyond the map is allocated.
  FLEETMAP_RETURN_IF_ERROR(transport::CheckUpdateRectangle(
      update.x, update.y, update.width, update.height, grid.width(), grid.height()));
  FLEETMAP_ASSIGN_OR_RETURN(
      const transport::MapUpdate inflated,
      transport::DecompressMapUpdate(update, static_cast<size_t>(grid.cell_count())));
  return Apply(inflated);
}

}  // namespace fleetmap::server
