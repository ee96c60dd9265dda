#include "common/fusion/grid_window.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <utility>

namespace fleetmap::fusion {
namespace {

TileRect BoundingRect(const std::vector<TileId>& tiles) {
  TileRect rect{tiles.front(), tiles.front()};
  for (const TileId& tile : tiles) {
    rect.min.x = std::min(rect.min.x, tile.x);
    rect.min.y = std::min(rect.min.y, tile.y);
    rect.max.x = std::max(rect.max.x, tile.x);
    rect.max.y = std::max(rect.max.y, tile.y);
  }
  return rect;
}

// The groups of tiles that lie at most `gap` empty tiles apart (Chebyshev distance gap + 1).
std::vector<std::vector<TileId>> GroupNearbyTiles(const std::vector<TileId>& tiles, int gap) {
  std::set<TileId> unvisited(tiles.begin(), tiles.end());
  const int64_t reach = int64_t{gap} + 1;
  std::vector<std::vector<TileId>> groups;
  while (!unvisited.empty()) {
    std::vector<TileId> group{*unvisited.begin()};
    unvisited.erase(unvisited.begin());
    for (size_t next = 0; next < group.size(); ++next) {
      const TileId at = group[next];
      // Look up the neighbours that exist, column by column: the set is sparse.
      for (int64_t x = int64_t{at.x} - reach; x <= int64_t{at.x} + reach; ++x) {
        if (x < INT32_MIN || x > INT32_MAX) continue;
        const auto y_lo = static_cast<int32_t>(std::max<int64_t>(int64_t{at.y} - reach, INT32_MIN));
        const int64_t y_hi = int64_t{at.y} + reach;
        auto it = unvisited.lower_bound(TileId{static_cast<int32_t>(x), y_lo});
        while (it != unvisited.end() && it->x == x && it->y <= y_hi) {
          group.push_back(*it);
          it = unvisited.erase(it);
        }
      }
    }
    groups.push_back(std::move(group));
  }
  return groups;
}

// The rectangle of at most max_tiles tiles centred on the group's median tile, cut to the group.
TileRect CutAroundMedian(std::vector<TileId> group, const TileRect& bounds, int64_t max_tiles) {
  const auto median = [&](auto coordinate) {
    std::vector<int32_t> values;
    values.reserve(group.size());
    for (const TileId& tile : group) values.push_back(coordinate(tile));
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return int64_t{values[values.size() / 2]};
  };
  const int64_t side = std::max<int64_t>(1, static_cast<int64_t>(std::sqrt(max_tiles)));
  const auto span = [&](int64_t centre, int32_t lo, int32_t hi) {
    int64_t first = std::clamp<int64_t>(centre - side / 2, lo, hi);
    const int64_t last = std::min<int64_t>(first + side - 1, hi);
    first = std::max<int64_t>(lo, last - side + 1);
    return std::pair{static_cast<int32_t>(first), static_cast<int32_t>(last)};
  };
  const auto [x0, x1] =
      span(median([](const TileId& t) { return t.x; }), bounds.min.x, bounds.max.x);
  const auto [y0, y1] =
      span(median([](const TileId& t) { return t.y; }), bounds.min.y, bounds.max.y);
  return TileRect{{x0, y0}, {x1, y1}};
}

}  // namespace

GridWindow ChooseGridWindow(const std::vector<SourcedTile>& tiles, int64_t max_tiles, int gap) {
  std::vector<TileId> keys;
  keys.reserve(tiles.size());
  for (const SourcedTile& tile : tiles) keys.push_back(tile.tile);
  GridWindow window;
  window.rect = BoundingRect(keys);
  if (window.rect.area() > max_tiles) {
    std::map<TileId, const SourcedTile*> source_of;
    for (const SourcedTile& tile : tiles) source_of[tile.tile] = &tile;
    // Ranked by how early it appeared, then by the robots that mapped it (larger is better).
    // Arrival order first: robot ids cost nothing to invent, and a peer claiming dozens of them
    // far away must not take the view from a fleet of a few robots that was there before it.
    const auto rank = [&](const std::vector<TileId>& group) {
      std::set<int> robots;
      uint64_t first_seen = UINT64_MAX;
      for (const TileId& tile : group) {
        const SourcedTile& source = *source_of.at(tile);
        robots.insert(source.robots.begin(), source.robots.end());
        first_seen = std::min(first_seen, source.first_seen);
      }
      return std::pair{UINT64_MAX - first_seen, robots.size()};
    };
    std::vector<std::vector<TileId>> groups = GroupNearbyTiles(keys, gap);
    size_t best = 0;
    auto best_rank = rank(groups[0]);
    for (size_t i = 1; i < groups.size(); ++i) {
      const auto candidate = rank(groups[i]);
      if (candidate > best_rank) {
        best = i;
        best_rank = candidate;
      }
    }
    window.rect = BoundingRect(groups[best]);
    if (window.rect.area() > max_tiles) {
      window.rect = CutAroundMedian(std::move(groups[best]), window.rect, max_tiles);
    }
  }
  for (const TileId& tile : keys) {
    if (window.rect.Contains(tile)) {
      ++window.tiles_shown;
    } else {
      ++window.tiles_left_out;
    }
  }
  return window;
}

}  // namespace fleetmap::fusion
