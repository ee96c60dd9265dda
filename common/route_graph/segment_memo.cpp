#include "common/route_graph/segment_memo.hpp"

#include <algorithm>
#include <limits>

namespace fleetmap::route_graph {

size_t SegmentMemo::KeyHash::operator()(const Key& key) const {
  uint64_t hash = 0xcbf29ce484222325ULL;
  for (const uint64_t word : key) {
    hash ^= word + 0x9e3779b97f4a7c15ULL + (hash << 6) + (hash >> 2);
  }
  return static_cast<size_t>(hash);
}

grid::CellRect SegmentMemo::CellsRead(const ClearanceMap& clearance, const Point2& a,
                                      const Point2& b) {
  const grid::CellIndex low =
      clearance.CellOf(Point2(std::min(a.x(), b.x()), std::min(a.y(), b.y())));
  const grid::CellIndex high =
      clearance.CellOf(Point2(std::max(a.x(), b.x()), std::max(a.y(), b.y())));
  // One cell around each sample's cell, and one more for rounding at the ends.
  return {low.x - 2, low.y - 2, high.x - low.x + 5, high.y - low.y + 5};
}

template <typename Walk>
double SegmentMemo::Remember(const ClearanceMap& clearance, const Key& key, const Point2& a,
                             const Point2& b, Walk&& walk) {
  const auto found = entries_.find(key);
  if (found != entries_.end()) return found->second.value;
  if (entries_.size() >= kMaxEntries) entries_.clear();
  const double value = walk();
  entries_.emplace(key, Entry{CellsRead(clearance, a, b), value});
  return value;
}

bool SegmentMemo::Keeps(const ClearanceMap& clearance, const Point2& a, const Point2& b,
                        double required) {
  const Key key = {Bits(a.x()), Bits(a.y()), Bits(b.x()), Bits(b.y()), Bits(required)};
  const double keeps = Remember(clearance, key, a, b,
                                [&] { return clearance.SegmentKeeps(a, b, required) ? 1.0 : 0.0; });
  return keeps > 0.5;
}

double SegmentMemo::Clearance(const ClearanceMap& clearance, const Point2& a, const Point2& b) {
  const Key key = {Bits(a.x()), Bits(a.y()), Bits(b.x()), Bits(b.y()),
                   Bits(std::numeric_limits<double>::quiet_NaN())};
  return Remember(clearance, key, a, b, [&] { return clearance.SegmentClearance(a, b); });
}

void SegmentMemo::Forget(const grid::CellRect& rect) {
  const auto overlaps = [&rect](const grid::CellRect& cells) {
    return cells.x0 < rect.x0 + rect.width && rect.x0 < cells.x0 + cells.width &&
           cells.y0 < rect.y0 + rect.height && rect.y0 < cells.y0 + cells.height;
  };
  std::erase_if(entries_, [&](const auto& entry) { return overlaps(entry.second.cells); });
}

}  // namespace fleetmap::route_graph
