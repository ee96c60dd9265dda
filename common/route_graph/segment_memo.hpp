#pragma once

// The clearance checks of a ClearanceMap's segments, remembered until the clearance under a
// segment changes. A route graph update re-traces the whole skeleton: straightening its curves,
// looking for shortcuts and measuring edges walk tens of thousands of segments, nearly all of them
// far from what changed. Here those are looked up; the ones near the change are walked again.
//
// Thread-safety: one thread (the builder's).

#include <array>
#include <cstdint>
#include <cstring>
#include <unordered_map>

#include "common/core/types.hpp"
#include "common/grid/cell_rect.hpp"
#include "common/route_graph/clearance_map.hpp"

namespace fleetmap::route_graph {

// Of one clearance map at a time: Forget() what changes under it, Clear() when it is made anew.
class SegmentMemo {
 public:
  // ClearanceMap::SegmentKeeps and ::SegmentClearance on `clearance`, remembered.
  bool Keeps(const ClearanceMap& clearance, const Point2& a, const Point2& b, double required);
  double Clearance(const ClearanceMap& clearance, const Point2& a, const Point2& b);

  // The clearance of the cells of `rect` changed: the segments whose walk reads them are walked
  // again when next asked.
  void Forget(const grid::CellRect& rect);
  // Everything (the clearance map was made anew).
  void Clear() { entries_.clear(); }
  size_t size() const { return entries_.size(); }

 private:
  // A segment's end points and what was asked of it (a required clearance, or NaN for the
  // clearance itself), bit for bit.
  using Key = std::array<uint64_t, 5>;
  struct KeyHash {
    size_t operator()(const Key& key) const;
  };
  struct Entry {
    grid::CellRect cells;  // every cell the walk may read
    double value = 0.0;    // 1 or 0 for Keeps, the clearance for Clearance
  };
  static uint64_t Bits(double value) {
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
  }
  // What the walk from `a` to `b` reads: the cells of its samples and their 3 x 3 neighbours.
  static grid::CellRect CellsRead(const ClearanceMap& clearance, const Point2& a, const Point2& b);
  template <typename Walk>
  double Remember(const ClearanceMap& clearance, const Key& key, const Point2& a, const Point2& b,
                  Walk&& walk);

  // Past this many segments the memo starts again: bounded memory on any map.
  static constexpr size_t kMaxEntries = size_t{1} << 20;

  std::unordered_map<Key, Entry, KeyHash> entries_;
};

}  // namespace fleetmap::route_graph
