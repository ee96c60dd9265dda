#pragma once

// Occupancy grid -> vector map (ALGORITHMS.md 1, docs/vector-maps.md).
//
// kDefault guarantees both constraints of the paper against every delimitation point: the
// epsilon-error constraint (every p in P within epsilon of an edge) and continuity (every point of
// every edge within epsilon of some p in P). It thins the occupied cells near obstacle boundaries
// to a one-cell skeleton (so a wall up to about 2 epsilon thick becomes one centre line), traces
// the skeleton into chains, and simplifies each chain greedily, accepting a shortcut only if every
// delimitation point attached to the chain stays within epsilon and the shortcut passes the exact
// continuity test. Delimitation points still uncovered afterwards (thick blobs, odd corners) are
// chained and simplified on their own, so the guarantee never depends on the skeleton. Centre
// lines are then moved off the cell centres where their painted band matches the cells better (a
// wall two cells thick: line_refit.hpp), each move checked against both constraints.
//
// kPaper is the paper's greedy shortcut removal, kept for comparison: it checks only the removed
// vertex and can break the epsilon-error constraint.
//
// Tiles: VectorizeTile() covers the delimitation points of one rectangle of cells. A skeleton chain
// that leaves the rectangle ends on the border line at a point computed only from the two rows of
// cells on either side of that border, so both tiles compute the same end point.
//
// Thread-safety: a Vectorizer is immutable; concurrent calls are safe.

#include <cstdint>
#include <string>
#include <utility>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/delimitation.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

enum class VectorizeMethod : uint8_t { kDefault, kPaper };

struct VectorizerOptions {
  VectorizeMethod method = VectorizeMethod::kDefault;
  // Metres; <= 0 picks DefaultEpsilon(resolution). Must be at least resolution * sqrt(2) / 2 (so
  // that two diagonal neighbours can always be joined).
  double epsilon = 0.0;
  bool extract_free_space = true;
  // Metres, the Douglas-Peucker tolerance of the free-space outlines; <= 0 picks epsilon.
  double free_epsilon = 0.0;
  grid::StateThresholds thresholds;
  std::string frame_id = "map";
  // Metres; > 0 puts every output vertex on the lattice lattice_origin + k * quantum (k integer,
  // map frame) and keeps both constraints after that snapping. The tile codec needs it.
  double quantum = 0.0;
  Point2 lattice_origin = Point2::Zero();
  // kDefault: move centre lines off the cell centres where the painted band then matches the
  // cells better (line_refit.hpp; both constraints still hold). Off only to measure its effect.
  bool refit_lines = true;

  void Describe(OptionsPrinter& out) const;
};

class Vectorizer {
 public:
  explicit Vectorizer(VectorizerOptions options = {}) : options_(std::move(options)) {}

  const VectorizerOptions& options() const { return options_; }
  // The epsilon (metres) used for a grid of this resolution.
  double EpsilonFor(double resolution) const;

  // The whole grid. Errors (kInvalidArgument): bad resolution or epsilon.
  StatusOr<VectorMap> Vectorize(const grid::OccupancyGrid& grid) const;
  // One rectangle of cells (must lie inside the grid); neighbours outside it are read from the
  // grid, so the union of the tiles of a grid satisfies the constraints for the whole grid.
  StatusOr<VectorMap> VectorizeTile(const grid::OccupancyGrid& grid, const CellRect& rect) const;

 private:
  VectorizerOptions options_;
};

}  // namespace fleetmap::vector_map
