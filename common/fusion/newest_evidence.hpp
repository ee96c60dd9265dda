#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::fusion {

// One contribution's cells as NewestEvidence reads them: 3-state values, each dated, all unknown
// outside [begin, end).
struct DatedCells {
  int slot = 0;  // which contribution of the tile: fixed while it exists
  const int8_t* values = nullptr;
  const uint32_t* dates = nullptr;
  size_t begin = 0;
  size_t end = 0;
};

// The fused cells of one tile, kept up to date contribution by contribution: per cell the newest
// evidence of a set of contributions (at equal dates an obstacle wins over free space; a free cell
// dated 0 is no evidence), its date, which contribution holds it, and the runner-up: the newest
// evidence of the others. Fusing a tile from scratch reads every known cell of every contribution,
// and a robot's new revision changes few of its cells: here only those are fused again (fusing
// from scratch was a third of the server's time, docs/results.md, "Robots per server core").
// With the holder and the runner-up, "the tile without one contribution" (what the quarantine
// weighs a robot against) needs no fusing at all.
//
// The caller says which contributions are in the set: a contribution leaves or joins it, or
// changes in a way not told through Change(), by Rebuild(). Not thread-safe.
class NewestEvidence {
 public:
  // All unknown, on the lattice of `empty`.
  explicit NewestEvidence(grid::OccupancyGrid empty);

  // The newest evidence of `contributions`, from scratch.
  void Rebuild(const std::vector<DatedCells>& contributions);
  // Contribution `slot` (in the set) now says `value` at `date` for cell `i`, where it said
  // `old_value` at `old_date`. Call for each cell that changed, then Settle() with the set as it
  // is now.
  void Change(int slot, size_t i, int8_t old_value, uint32_t old_date, int8_t value, uint32_t date);
  // Fuses again the cells where the holder or the runner-up said less in Change().
  void Settle(const std::vector<DatedCells>& contributions);

  // The fused cells and their evidence dates (0: unknown).
  const grid::OccupancyGrid& cells() const { return cells_; }
  // The memory it holds: 11 bytes a cell (440 KB for a 10 m tile of 5 cm cells).
  size_t HeldBytes() const;
  const std::vector<uint32_t>& dates() const { return dates_; }
  // The cells and dates of `contributions` without `slot`: what the set says when that
  // contribution is left out. `contributions` is the set (with or without `slot`).
  void Without(int slot, const std::vector<DatedCells>& contributions, grid::OccupancyGrid* cells,
               std::vector<uint32_t>* dates) const;

 private:
  // Holders past this many share one mark: a cell so marked is fused again when any of them
  // leaves or lowers it (exact, only slower), and the holders take one byte per cell.
  static constexpr int kSharedHolder = 255;
  static uint8_t HolderOf(int slot) {
    return static_cast<uint8_t>(slot < kSharedHolder ? slot : kSharedHolder);
  }
  // Orders evidence as the fusion does: newer first, then an obstacle over free space; 0 for
  // unknown (and for free space dated 0, which never wins over nothing).
  static uint64_t Key(int8_t value, uint32_t date) {
    const uint64_t known = value != grid::kUnknownValue ? 1 : 0;
    return known * ((uint64_t{date} << 1) | (value == grid::kOccupiedValue ? 1 : 0));
  }
  static int8_t ValueOf(uint64_t key) {
    return key == 0 ? grid::kUnknownValue
                    : ((key & 1) != 0 ? grid::kOccupiedValue : grid::kFreeValue);
  }
  static uint32_t DateOf(uint64_t key) { return static_cast<uint32_t>(key >> 1); }
  // Per cell: the newest key, the contribution that has it, and the newest of the others'.
  struct Fused {
    uint64_t best = 0;
    uint64_t runner_up = 0;
    uint8_t holder = 0;

    void Take(uint64_t key, uint8_t from) {
      if (key > best) {
        runner_up = best;
        best = key;
        holder = from;
      } else if (key > runner_up) {
        runner_up = key;
      }
    }
  };
  // The cells `cells` (ascending) fused again from `contributions` leaving out `skip` (-1: none),
  // contribution by contribution so that each one's cells are read in order.
  static std::vector<Fused> FuseAgain(const std::vector<size_t>& cells,
                                      const std::vector<DatedCells>& contributions, int skip);
  void Set(size_t i, const Fused& fused);
  uint64_t BestKey(size_t i) const { return Key(cells_.data()[i], dates_[i]); }
  uint64_t RunnerUpKey(size_t i) const { return Key(runner_up_values_[i], runner_up_dates_[i]); }

  grid::OccupancyGrid cells_;
  std::vector<uint32_t> dates_;
  std::vector<uint8_t> holders_;
  // The runner-up, as value and date (5 bytes a cell, not a key's 8: tiles are many).
  std::vector<int8_t> runner_up_values_;
  std::vector<uint32_t> runner_up_dates_;
  std::vector<size_t> to_settle_;
};

}  // namespace fleetmap::fusion
