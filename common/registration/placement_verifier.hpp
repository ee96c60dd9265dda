#pragma once

// Verification of a candidate placement of map B on map A at full resolution: how many of each
// map's occupied cells meet an occupied cell of the other (agree) and how many land on the
// other's free space with none near (contradict). Internal to the registration module
// (registration.cpp chooses between candidates with it); see docs/registration.md.
//
// Drift. A SLAM map bends and stretches as its robot drives (scale errors of a percent or two, a
// heading that creeps), so no rigid transform lays a drifted B on A everywhere: the walls far from
// where the two maps meet land a few cells off, miss A's walls and cross its free space. Judged
// rigidly, a right placement of a drifted map verifies like a wrong one. The drift-tolerant
// verification lets each block of B (a few metres square) move by a small shift of its own, no
// larger than the drift could have made it there: max_drift_per_m of its distance from the
// centre of the agreement, at most max_drift_cells. The placement stays one rigid transform; the
// shifts only decide what counts as agreeing.

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::registration {

struct RegistrationOptions;

// A rigid transform between the grids' own frames (metres from cell (0, 0)'s outer corner).
struct GridTransform {
  double yaw = 0.0;
  double tx = 0.0;
  double ty = 0.0;
  // Inline, so that loops over many points hoist the sine and cosine out.
  Point2 Apply(const Point2& p) const {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {c * p.x() - s * p.y() + tx, s * p.x() + c * p.y() + ty};
  }
  GridTransform Inverse() const;
};

// The centres (grid metres) of g's cells in `state`, evenly thinned to at most `max_points`.
std::vector<Point2> CellCentres(const grid::OccupancyGrid& g, grid::CellState state, int max_points,
                                const grid::StateThresholds& thresholds);

// The shift each block of B takes on A (A's grid metres), blocks `block` metres square on B's
// grid. Empty when the verification was rigid.
class DriftCorrection {
 public:
  DriftCorrection() = default;
  DriftCorrection(double block, int columns, int rows);

  bool empty() const { return shifts_.empty(); }
  // The shift of the block holding `b_point` (B's grid metres); points outside B's grid take
  // the nearest block's.
  Point2 ShiftAt(const Point2& b_point) const;
  void Set(int block_index, const Point2& shift) {
    shifts_[static_cast<size_t>(block_index)] = shift;
  }
  int BlockOf(const Point2& b_point) const;
  int block_count() const { return static_cast<int>(shifts_.size()); }
  // B-grid metres of a block's centre.
  Point2 BlockCentre(int block_index) const;
  // The largest shift's length (metres).
  double Largest() const;

 private:
  double block_ = 0.0;
  int columns_ = 0;
  int rows_ = 0;
  std::vector<Point2> shifts_;
};

// Occupied cells counted on every cell (not samples), the winner's figures.
struct Evidence {
  int64_t known = 0;            // `from` cells known
  int64_t known_shared = 0;     // ... landing on a known `to` cell
  int64_t occupied_shared = 0;  // `from` occupied cells landing on a known `to` cell
  int64_t agree = 0;            // `from` occupied cells with a `to` occupied cell near
  int64_t contradict = 0;       // `from` occupied cells on a free `to` cell with none near
};

// Where two placements disagree: occupied cells (of either map, every cell) that one placement
// lays on the other map's walls and the other on its free space with no wall near.
struct Discrimination {
  int64_t for_first = 0;   // agree under the first placement, contradict under the second
  int64_t for_second = 0;  // the reverse
};

class PlacementVerifier {
 public:
  struct Verdict {
    double agree = 0.0;       // occupied cells, both ways
    double contradict = 0.0;  // occupied cells, both ways
    double value = 0.0;       // agree - w * contradict
    DriftCorrection drift;    // the blocks' shifts, when verified with drift
  };

  PlacementVerifier(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b,
                    const RegistrationOptions& options);

  // Scores `t` (B's grid metres to A's) from thinned samples of both maps, so that many
  // candidates can be compared for little more than one; samples stand for all the cells they
  // were thinned from, so the figures are cell counts.
  Verdict Verify(const GridTransform& t) const;
  // The same with each block of B shifted as drift could have (see the file comment); rigid when
  // the options allow no drift.
  Verdict VerifyWithDrift(const GridTransform& t) const;

  // The winner's figures on every cell, both directions, each of B's cells moved by its block's
  // shift (none when `drift` is empty).
  Evidence BInA(const GridTransform& t, const DriftCorrection& drift) const;
  Evidence AInB(const GridTransform& t, const DriftCorrection& drift) const;
  // Two placements compared only where they disagree (each with its drift correction): the
  // evidence that tells a placement from its twin on repeated structure, which the whole-map
  // figures dilute with the walls both explain (a warehouse's racks against its pallets).
  Discrimination Discriminate(const GridTransform& first, const DriftCorrection& first_drift,
                              const GridTransform& second,
                              const DriftCorrection& second_drift) const;

 private:
  static constexpr uint8_t kUnknown = 0, kFree = 1, kOccupied = 2;
  struct Side {
    int width = 0, height = 0;
    double res = 1.0;
    std::vector<uint8_t> state;
    std::vector<uint8_t> near_occupied;  // an occupied cell within the tolerance
    std::vector<Point2> occupied_points;
    double occupied_weight = 1.0;  // cells per sample
    int64_t Index(const Point2& p) const;
    // An occupied cell of the other map landing at `index`: +1 on a wall (within the tolerance),
    // -1 on free space with none near, 0 on unknown or off the grid.
    int Judge(int64_t index) const;
  };
  struct Tally {
    double agree = 0.0, contradict = 0.0;
    void Add(const Side& to, int64_t index, double weight);
    double Value(double contradiction_weight) const {
      return agree - contradiction_weight * contradict;
    }
  };

  static Side MakeSide(const grid::OccupancyGrid& g, const RegistrationOptions& options);
  static Tally Occupied(const Side& from, const Side& to, const GridTransform& t);
  // `moved` takes a `from` grid point to the `to` grid.
  template <typename Move>
  static Evidence CompareCells(const Side& from, const Side& to, Move moved);
  template <typename MoveFirst, typename MoveSecond>
  static void CountDisagreements(const Side& from, const Side& to, MoveFirst first,
                                 MoveSecond second, Discrimination* d);
  // The shift (A's grid metres) of each block, chosen as the one that verifies best within what
  // drift allows at the block's distance from `anchor` (A's grid metres).
  Verdict ShiftBlocks(const GridTransform& t, const Point2& anchor) const;

  Side a_;
  Side b_;
  double contradiction_weight_;
  double drift_block_m_;
  double max_drift_per_m_;
  int max_drift_cells_;
};

}  // namespace fleetmap::registration
