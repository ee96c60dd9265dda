#include "common/fusion/fusion_options.hpp"

#include <cmath>
#include <string>

namespace fleetmap::fusion {

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
  return Status::Ok();
}

int FusionOptions::CellsPerTile() const {
  return static_cast<int>(std::lround(tile_size / resolution));
}

double FusionOptions::FusedResolution() const { return tile_size / CellsPerTile(); }

}  // namespace fleetmap::fusion
