#include "common/fusion/fusion_options.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace fleetmap::fusion {

Status QuarantineOptions::Validate() const {
  const auto bad = [](double v) { return !std::isfinite(v) || v < 0.0; };
  if (bad(tolerance_m) || tolerance_m > 5.0) {
    return InvalidArgumentError("quarantine tolerance_m must be in [0, 5] m");
  }
  if (bad(min_contradicted_m) || bad(max_contradicted_m) ||
      max_contradicted_m < min_contradicted_m) {
    return InvalidArgumentError(
        "quarantine min_contradicted_m and max_contradicted_m must be >= 0, max >= min");
  }
  if (bad(enter_share) || enter_share > 1.0 || bad(leave_share) || leave_share > enter_share) {
    return InvalidArgumentError(
        "quarantine shares must satisfy 0 <= leave_share <= enter_share <= 1");
  }
  if (bad(corroborate_share) || corroborate_share > 1.0) {
    return InvalidArgumentError("quarantine corroborate_share must be in [0, 1]");
  }
  return Status::Ok();
}

void QuarantineOptions::Describe(OptionsPrinter& out) const {
  out.Add("enabled", enabled);
  out.Add("tolerance_m", tolerance_m);
  out.Add("min_contradicted_m", min_contradicted_m);
  out.Add("enter_share", enter_share);
  out.Add("max_contradicted_m", max_contradicted_m);
  out.Add("leave_share", leave_share);
  out.Add("corroborate_share", corroborate_share);
}

Status FusionOptions::Validate() const {
  if (!std::isfinite(tile_size) || tile_size <= 0.0) {
    return InvalidArgumentError("fusion tile_size " + std::to_string(tile_size) +
                                " m is not a positive number");
  }
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    return InvalidArgumentError("fusion resolution " + std::to_string(resolution) +
                                " m is not a positive number");
  }
  const double cells = tile_size / resolution;
  if (cells < 4.0 || cells > 4096.0) {
    return InvalidArgumentError("a fused tile of " + std::to_string(tile_size) + " m at " +
                                std::to_string(resolution) + " m has " + std::to_string(cells) +
                                " cells per side; 4..4096 are supported");
  }
  if (margin_cells < 0 || margin_cells > CellsPerTile()) {
    return InvalidArgumentError("fusion margin_cells must be in 0..cells per tile");
  }
  if (!std::isfinite(max_coordinate) || max_coordinate < tile_size) {
    return InvalidArgumentError("fusion max_coordinate must be at least one tile");
  }
  if (max_grid_cells < static_cast<int64_t>(CellsPerTile()) * CellsPerTile()) {
    return InvalidArgumentError(
        "the fused grid's cell budget (--max-map-cells) " + std::to_string(max_grid_cells) +
        " must hold at least one tile of " + std::to_string(CellsPerTile()) + " x " +
        std::to_string(CellsPerTile()) + " cells");
  }
  return quarantine.Validate();
}

Status FusionOptions::CheckTileInRange(const TileId& tile) const {
  // The far corner of the tile, computed in double: tile keys are any int32 on the wire.
  const double reach =
      (std::max(std::abs(static_cast<double>(tile.x)), std::abs(static_cast<double>(tile.y))) +
       1.0) *
      tile_size;
  if (reach <= max_coordinate) return Status::Ok();
  return InvalidArgumentError("tile (" + std::to_string(tile.x) + ", " + std::to_string(tile.y) +
                              ") lies " + std::to_string(reach) +
                              " m from the fleet origin, beyond the " +
                              std::to_string(max_coordinate) + " m this server accepts");
}

int FusionOptions::CellsPerTile() const {
  return static_cast<int>(std::lround(tile_size / resolution));
}

double FusionOptions::FusedResolution() const { return tile_size / CellsPerTile(); }

void FusionOptions::Describe(OptionsPrinter& out) const {
  out.Add("tile_size", tile_size);
  out.Add("resolution", resolution);
  out.Add("margin_cells", margin_cells);
  out.Nested("vectorizer", vectorizer);
  out.Add("max_coordinate", max_coordinate);
  out.Add("max_grid_cells", max_grid_cells);
  out.Nested("quarantine", quarantine);
}

}  // namespace fleetmap::fusion
