#pragma once

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/vector_map/vectorizer.hpp"

namespace fleetmap::fusion {

// When a robot's map contradicts what the rest of the fleet has established, and when it agrees
// again (docs/fleet.md, "Quarantine"). A robot's free cell contradicts the fleet where other
// trusted robots' evidence says occupied, that evidence is older than the robot's, the robot has
// no occupied cell within tolerance_m of it, and no robot of another participant has seen the
// cell free since. Such a robot is quarantined: its tiles are kept, not fused.
struct QuarantineOptions {
  bool enabled = true;
  // Two honest maps of one wall disagree by SLAM noise, drift and registration error; a robot
  // shifted 2 m or turned 10 degrees disagrees by more than this over most of its walls.
  double tolerance_m = 0.3;
  // Quarantined when its contradicted cells cover at least min_contradicted_m of wall (in cells
  // of the fused resolution) and at least enter_share of the established occupied cells it sees,
  // or max_contradicted_m of wall whatever the share (a peer cannot dilute what it erases by
  // echoing the fleet's walls elsewhere).
  double min_contradicted_m = 2.0;
  double enter_share = 0.1;
  double max_contradicted_m = 10.0;
  // A quarantined robot leaves when it contradicts less than min_contradicted_m, or less than
  // leave_share of what it sees (relocalized, or the change confirmed by another robot).
  double leave_share = 0.04;
  // A robot is corroborated once robots of other participants confirm min_contradicted_m of its
  // walls (an occupied cell of theirs within tolerance_m) and at least this share of its walls
  // they know. Evidence of robots nobody corroborated never quarantines a corroborated robot: a
  // robot that lost its localization, or a peer inventing walls, in space the fleet had not
  // seen yet must not turn the robots that map it next into the contradicting ones.
  double corroborate_share = 0.5;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

struct FusionOptions {
  double tile_size = 10.0;   // metres: the fleet tiling every robot publishes in
  double resolution = 0.05;  // metres per fused cell; adjusted so a tile holds whole cells
  // Cells of context taken from the neighbouring fused tiles when a tile is vectorized, so that
  // walls crossing a border end at the same point in both tiles.
  int margin_cells = 4;
  vector_map::VectorizerOptions vectorizer;
  // Tiles further than this from the fleet origin are refused: UTM northings stay below 1e7 m,
  // and beyond 2e7 m no place on Earth is meant.
  double max_coordinate = 2e7;
  // Cells of the one grid FusedGrid() builds for rt/fleetmap/map (a nav_msgs/OccupancyGrid must
  // be dense). When the fused tiles span more, it shows the largest group of nearby tiles.
  int64_t max_grid_cells = int64_t{1} << 26;  // 64 M cells: 8192 x 8192, 410 m square at 5 cm
  QuarantineOptions quarantine;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
  // Whether `tile` lies within max_coordinate of the origin; the error names it otherwise.
  Status CheckTileInRange(const TileId& tile) const;
  // Cells along one side of a tile, and the exact resolution that fits them.
  int CellsPerTile() const;
  double FusedResolution() const;
};

}  // namespace fleetmap::fusion
