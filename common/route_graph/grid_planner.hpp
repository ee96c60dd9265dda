#pragma once

// The grid planner the route graph is checked against: A* over the cells where the robot fits
// (clearance >= the robot's radius plus margin, i.e. the grid inflated by them), 8-connected with
// Euclidean step costs; and the parts of that space (which cells it connects at all).
//
// Thread-safety: const methods may be called from any number of threads; the planner refers to
// the clearance map it was made with, which must outlive it.

#include <cstdint>
#include <optional>
#include <vector>

#include "common/grid/occupancy_grid.hpp"
#include "common/route_graph/clearance_map.hpp"

namespace fleetmap::route_graph {

class GridPlanner {
 public:
  // Cells with clearance >= `required` are traversable.
  GridPlanner(const ClearanceMap& clearance, double required);

  bool Traversable(const grid::CellIndex& cell) const;
  // The part of traversable space a cell is in (-1 for a cell that is not traversable).
  int Component(const grid::CellIndex& cell) const;
  // Every traversable cell, row-major.
  std::vector<grid::CellIndex> TraversableCells() const;
  // The length (metres, centre to centre) of the shortest 8-connected path, or nothing.
  std::optional<double> PathLength(const grid::CellIndex& from, const grid::CellIndex& to) const;

 private:
  size_t Index(const grid::CellIndex& cell) const {
    return static_cast<size_t>(cell.y) * clearance_.width() + cell.x;
  }

  const ClearanceMap& clearance_;
  double required_;
  std::vector<int> component_;
};

}  // namespace fleetmap::route_graph
