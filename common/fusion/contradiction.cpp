#include "common/fusion/contradiction.hpp"

#include <algorithm>

#include "common/core/check.hpp"

namespace fleetmap::fusion {
namespace {

// How far a breach is looked for on each side of a wall cell: walls up to 2 m thick (at 5 cm).
constexpr int kBreachReachCells = 20;

// Whether each cell has an occupied cell of `cells` within `radius` (a square window), in
// O(cells): a running count along the rows, then along the columns.
std::vector<uint8_t> OccupiedWithin(const grid::OccupancyGrid& cells, int radius) {
  const int w = cells.width();
  const int h = cells.height();
  std::vector<uint8_t> rows(static_cast<size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y) {
    const int8_t* row = &cells.data()[static_cast<size_t>(y) * w];
    int count = 0;
    // The window [x - radius, x + radius], slid along the row.
    for (int x = 0; x < std::min(radius, w); ++x) count += row[x] == grid::kOccupiedValue;
    for (int x = 0; x < w; ++x) {
      if (x + radius < w) count += row[x + radius] == grid::kOccupiedValue;
      if (x - radius - 1 >= 0) count -= row[x - radius - 1] == grid::kOccupiedValue;
      rows[static_cast<size_t>(y) * w + x] = count > 0;
    }
  }
  std::vector<uint8_t> near(rows.size(), 0);
  for (int x = 0; x < w; ++x) {
    int count = 0;
    for (int y = 0; y < std::min(radius, h); ++y) count += rows[static_cast<size_t>(y) * w + x];
    for (int y = 0; y < h; ++y) {
      if (y + radius < h) count += rows[static_cast<size_t>(y + radius) * w + x];
      if (y - radius - 1 >= 0) count -= rows[static_cast<size_t>(y - radius - 1) * w + x];
      near[static_cast<size_t>(y) * w + x] = count > 0;
    }
  }
  return near;
}

// Whether the robot's free space breaches the fleet's wall at (x, y): along one of four
// directions, walking both ways from the cell, every cell of the fleet's wall is free to the robot
// until the wall ends within `reach` cells on each side, where the robot calls the cell free or
// the fleet does (a robot need not have seen behind a wall to open it). Scans that graze a wall
// clear its near face, not its whole thickness: they stop at it, and what they clear runs along
// the wall, which does not end within the reach. A map shifted or turned over the fleet's rooms,
// free space painted by a peer up to or beyond a wall, a shelf row taken away: each opens walls.
bool Breaches(const grid::OccupancyGrid& robot, const grid::OccupancyGrid& fleet, int x, int y,
              int reach) {
  constexpr int kDirections[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  // Walks from (x, y) by (dx, dy): the side of a breach when the wall ends within the reach.
  const auto opens = [&](int dx, int dy, bool* robot_free_beyond) {
    for (int step = 1; step <= reach; ++step) {
      const int cx = x + dx * step;
      const int cy = y + dy * step;
      if (!robot.Contains(cx, cy)) return false;
      const bool robot_free = robot.at(cx, cy) == grid::kFreeValue;
      if (fleet.at(cx, cy) == grid::kOccupiedValue) {
        if (!robot_free) return false;  // the robot leaves this part of the wall standing
        continue;
      }
      *robot_free_beyond = robot_free;
      return robot_free || fleet.at(cx, cy) == grid::kFreeValue;
    }
    return false;  // still wall: along it, or thicker than the reach
  };
  for (const auto& [dx, dy] : kDirections) {
    bool ahead_free = false;
    bool behind_free = false;
    // The robot's own free space on at least one side: it opens the wall from where it is.
    if (opens(dx, dy, &ahead_free) && opens(-dx, -dy, &behind_free) &&
        (ahead_free || behind_free)) {
      return true;
    }
  }
  return false;
}

}  // namespace

TileContradiction CountContradiction(const grid::OccupancyGrid& robot_cells,
                                     const std::vector<uint32_t>& robot_dates,
                                     const EstablishedCells& established, int tolerance_cells) {
  FLEETMAP_CHECK(established.cells != nullptr && established.dates != nullptr,
                 "CountContradiction needs the established cells and their dates");
  const grid::OccupancyGrid& fleet = *established.cells;
  FLEETMAP_CHECK(fleet.width() == robot_cells.width() && fleet.height() == robot_cells.height() &&
                     robot_dates.size() == robot_cells.data().size() &&
                     established.dates->size() == fleet.data().size(),
                 "CountContradiction needs cells on one lattice");
  const std::vector<uint32_t>* confirmed = established.confirmed_free_at;
  FLEETMAP_CHECK(
      confirmed == nullptr || confirmed->empty() || confirmed->size() == fleet.data().size(),
      "CountContradiction: confirmations on another lattice");
  if (confirmed != nullptr && confirmed->empty()) confirmed = nullptr;

  TileContradiction out;
  std::vector<uint8_t> robot_wall_near;  // computed once a candidate shows up
  const int w = fleet.width();
  for (int y = 0; y < fleet.height(); ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (fleet.data()[i] != grid::kOccupiedValue) continue;
      const int8_t mine = robot_cells.data()[i];
      if (mine == grid::kUnknownValue) continue;
      ++out.established_seen;
      if (mine != grid::kFreeValue) continue;
      const uint32_t fleet_date = (*established.dates)[i];
      if (robot_dates[i] <= fleet_date) continue;  // older evidence: it does not win anyway
      if (confirmed != nullptr && (*confirmed)[i] > fleet_date) continue;
      if (robot_wall_near.empty()) robot_wall_near = OccupiedWithin(robot_cells, tolerance_cells);
      if (robot_wall_near[i] != 0) continue;
      if (!Breaches(robot_cells, fleet, x, y, kBreachReachCells)) continue;
      ++out.contradicted;
      out.min_x = out.contradicted == 1 ? x : std::min(out.min_x, x);
      out.min_y = out.contradicted == 1 ? y : std::min(out.min_y, y);
      out.max_x = std::max(out.max_x, x);
      out.max_y = std::max(out.max_y, y);
    }
  }
  return out;
}

void CountAgreement(const grid::OccupancyGrid& robot_cells, const grid::OccupancyGrid& others,
                    int tolerance_cells, TileContradiction* counted) {
  FLEETMAP_CHECK(others.width() == robot_cells.width() && others.height() == robot_cells.height(),
                 "CountAgreement needs cells on one lattice");
  counted->walls_known = 0;
  counted->walls_confirmed = 0;
  std::vector<uint8_t> others_wall_near;  // computed once a known wall shows up
  const size_t cells = robot_cells.data().size();
  for (size_t i = 0; i < cells; ++i) {
    if (robot_cells.data()[i] != grid::kOccupiedValue) continue;
    if (others.data()[i] == grid::kUnknownValue) continue;
    ++counted->walls_known;
    if (others_wall_near.empty()) others_wall_near = OccupiedWithin(others, tolerance_cells);
    if (others_wall_near[i] != 0) ++counted->walls_confirmed;
  }
}

}  // namespace fleetmap::fusion
