#include "bench/extrapolation/room_segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>

#include <Eigen/Eigenvalues>

namespace fleetmap::bench {
namespace {

constexpr int kDx4[4] = {1, -1, 0, 0};
constexpr int kDy4[4] = {0, 0, 1, -1};

// Chamfer distance (metres) from each cell to the nearest cell of `target` (row-major, w x h);
// cells off the grid count as targets when `off_grid_is_target`.
std::vector<double> DistanceTo(const std::vector<uint8_t>& target, int w, int h, double r,
                               bool off_grid_is_target) {
  const double d = r * std::sqrt(2.0);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(target.size(), inf);
  for (size_t i = 0; i < target.size(); ++i) {
    if (target[i]) dist[i] = 0.0;
  }
  auto at = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= w || y >= h) return off_grid_is_target ? 0.0 : inf;
    return dist[static_cast<size_t>(y) * w + x];
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double& v = dist[static_cast<size_t>(y) * w + x];
      v = std::min(
          {v, at(x - 1, y) + r, at(x, y - 1) + r, at(x - 1, y - 1) + d, at(x + 1, y - 1) + d});
    }
  }
  for (int y = h - 1; y >= 0; --y) {
    for (int x = w - 1; x >= 0; --x) {
      double& v = dist[static_cast<size_t>(y) * w + x];
      v = std::min(
          {v, at(x + 1, y) + r, at(x, y + 1) + r, at(x + 1, y + 1) + d, at(x - 1, y + 1) + d});
    }
  }
  return dist;
}

// Chamfer distance (metres) from each free cell to the nearest cell that is not free; 0 elsewhere.
// Off the map counts as not free, so a room cut by the map's edge is not mistaken for open.
std::vector<double> Clearance(const grid::OccupancyGrid& map) {
  std::vector<uint8_t> not_free(static_cast<size_t>(map.cell_count()), 0);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      not_free[static_cast<size_t>(y) * map.width() + x] =
          map.StateAt(x, y) != grid::CellState::kFree ? 1 : 0;
    }
  }
  return DistanceTo(not_free, map.width(), map.height(), map.resolution(), true);
}

}  // namespace

std::vector<uint8_t> SegmentBuilding(const grid::OccupancyGrid& map, double closing_radius) {
  const int w = map.width(), h = map.height();
  const double r = map.resolution();
  std::vector<uint8_t> known(static_cast<size_t>(map.cell_count()), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      known[static_cast<size_t>(y) * w + x] = map.StateAt(x, y) != grid::CellState::kUnknown;
    }
  }
  // Closing: grown by the radius, then shrunk by it (off the grid is not the building, so the
  // shrinking starts at the grid's edge too); the known cells themselves always stay.
  const std::vector<double> to_known = DistanceTo(known, w, h, r, false);
  std::vector<uint8_t> outside_grown(known.size(), 0);
  for (size_t i = 0; i < known.size(); ++i) outside_grown[i] = to_known[i] > closing_radius;
  const std::vector<double> to_outside = DistanceTo(outside_grown, w, h, r, true);
  std::vector<uint8_t> closed(known.size(), 0);
  for (size_t i = 0; i < known.size(); ++i) {
    closed[i] = known[i] || to_outside[i] > closing_radius;
  }
  // Holes filled: what the grid's edge reaches through cells off the closed set is outside.
  std::vector<uint8_t> outside(known.size(), 0);
  std::deque<size_t> queue;
  const auto push = [&](int x, int y) {
    const size_t i = static_cast<size_t>(y) * w + x;
    if (!closed[i] && !outside[i]) {
      outside[i] = 1;
      queue.push_back(i);
    }
  };
  for (int x = 0; x < w; ++x) push(x, 0), push(x, h - 1);
  for (int y = 0; y < h; ++y) push(0, y), push(w - 1, y);
  while (!queue.empty()) {
    const size_t i = queue.front();
    queue.pop_front();
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    for (int k = 0; k < 4; ++k) {
      const int nx = x + kDx4[k], ny = y + kDy4[k];
      if (nx >= 0 && ny >= 0 && nx < w && ny < h) push(nx, ny);
    }
  }
  std::vector<uint8_t> inside(known.size(), 0);
  for (size_t i = 0; i < known.size(); ++i) inside[i] = !outside[i];
  return inside;
}

RoomSegmentation SegmentRooms(const grid::OccupancyGrid& map,
                              const RoomSegmentationOptions& options) {
  const int w = map.width(), h = map.height();
  const double r = map.resolution(), cell_area = r * r;
  const std::vector<double> clearance = Clearance(map);
  RoomSegmentation seg;
  seg.labels.assign(static_cast<size_t>(map.cell_count()), -1);
  std::vector<int32_t>& labels = seg.labels;

  // Room cores: connected components of the eroded free space, the small ones dropped.
  std::deque<size_t> frontier;
  int32_t rooms = 0;
  for (size_t start = 0; start < labels.size(); ++start) {
    if (labels[start] != -1 || clearance[start] <= options.core_clearance) continue;
    std::vector<size_t> component = {start};
    labels[start] = rooms;
    for (size_t k = 0; k < component.size(); ++k) {
      const int x = static_cast<int>(component[k] % w), y = static_cast<int>(component[k] / w);
      for (int n = 0; n < 4; ++n) {
        const int nx = x + kDx4[n], ny = y + kDy4[n];
        if (!map.Contains(nx, ny)) continue;
        const size_t j = static_cast<size_t>(ny) * w + nx;
        if (labels[j] != -1 || clearance[j] <= options.core_clearance) continue;
        labels[j] = rooms;
        component.push_back(j);
      }
    }
    if (static_cast<double>(component.size()) * cell_area < options.min_core_area) {
      for (size_t i : component) labels[i] = -2;  // seen, not a core
      continue;
    }
    frontier.insert(frontier.end(), component.begin(), component.end());
    ++rooms;
  }
  for (int32_t& l : labels) l = l == -2 ? -1 : l;

  // Grow the cores back through the free space, all at once, so each free cell joins the nearest.
  while (!frontier.empty()) {
    const size_t i = frontier.front();
    frontier.pop_front();
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    for (int n = 0; n < 4; ++n) {
      const int nx = x + kDx4[n], ny = y + kDy4[n];
      if (!map.Contains(nx, ny)) continue;
      const size_t j = static_cast<size_t>(ny) * w + nx;
      if (labels[j] != -1 || clearance[j] <= 0.0) continue;
      labels[j] = labels[i];
      frontier.push_back(j);
    }
  }

  // Where rooms touch: per ordered pair (room, other), the cells of `other` next to `room`.
  seg.room_area.assign(static_cast<size_t>(rooms), 0.0);
  seg.neighbours.assign(static_cast<size_t>(rooms), {});
  std::map<std::pair<int32_t, int32_t>, std::vector<size_t>> touching;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (labels[i] < 0) continue;
      seg.room_area[labels[i]] += cell_area;
      for (int n = 0; n < 4; ++n) {
        const int nx = x + kDx4[n], ny = y + kDy4[n];
        if (!map.Contains(nx, ny)) continue;
        const int32_t other = labels[static_cast<size_t>(ny) * w + nx];
        if (other < 0 || other == labels[i]) continue;
        std::vector<size_t>& cells = touching[{other, labels[i]}];
        if (cells.empty() || cells.back() != i) cells.push_back(i);
      }
    }
  }
  for (const auto& [pair, cells] : touching) seg.neighbours[pair.first].push_back(pair.second);

  for (int32_t room = 0; room < rooms; ++room) {
    if (seg.room_area[room] < options.min_room_area ||
        seg.room_area[room] > options.max_room_area || seg.neighbours[room].size() != 1) {
      continue;
    }
    SegmentedDoorway door;
    door.room = room;
    door.other = seg.neighbours[room].front();
    door.leaf_cells = touching.at({room, door.other});
    std::sort(door.leaf_cells.begin(), door.leaf_cells.end());
    door.leaf_cells.erase(std::unique(door.leaf_cells.begin(), door.leaf_cells.end()),
                          door.leaf_cells.end());
    // The leaf's line: the principal axis of its cells; its ends half a cell past the outer ones.
    Point2 mean = Point2::Zero();
    for (size_t i : door.leaf_cells)
      mean += map.CellCenter(static_cast<int>(i % w), static_cast<int>(i / w));
    mean /= static_cast<double>(door.leaf_cells.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (size_t i : door.leaf_cells) {
      const Vector2 v = map.CellCenter(static_cast<int>(i % w), static_cast<int>(i / w)) - mean;
      cov += v * v.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(cov);
    const Vector2 axis = eigen.eigenvectors().col(1);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (size_t i : door.leaf_cells) {
      const double s =
          (map.CellCenter(static_cast<int>(i % w), static_cast<int>(i / w)) - mean).dot(axis);
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
    door.jamb_a = mean + (lo - 0.5 * r) * axis;
    door.jamb_b = mean + (hi + 0.5 * r) * axis;
    door.width = (door.jamb_b - door.jamb_a).norm();
    if (door.width < options.min_door_width || door.width > options.max_door_width) continue;
    // Into the room: from the leaf towards the room's cells that touch it, across the axis.
    Point2 room_side = Point2::Zero();
    const std::vector<size_t>& inside = touching.at({door.other, room});
    for (size_t i : inside)
      room_side += map.CellCenter(static_cast<int>(i % w), static_cast<int>(i / w));
    room_side /= static_cast<double>(inside.size());
    const Vector2 normal(-axis.y(), axis.x());
    door.into_room = (room_side - mean).dot(normal) >= 0.0 ? normal : Vector2(-normal);
    seg.doorways.push_back(std::move(door));
  }
  return seg;
}

FloorPlan PlanForRoom(const grid::OccupancyGrid& map, const RoomSegmentation& segmentation,
                      const SegmentedDoorway& doorway, const RoomSegmentationOptions& options,
                      const std::vector<uint8_t>& building) {
  const int w = map.width(), h = map.height();
  const double r = map.resolution();
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (segmentation.labels[static_cast<size_t>(y) * w + x] != doorway.room) continue;
      x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
  }
  const int margin = static_cast<int>(std::ceil(options.crop_margin / r));
  x0 = std::max(0, x0 - margin), y0 = std::max(0, y0 - margin);
  x1 = std::min(w - 1, x1 + margin), y1 = std::min(h - 1, y1 + margin);
  const int cw = x1 - x0 + 1, ch = y1 - y0 + 1;
  const Point2 corner = map.CellCenter(x0, y0);
  FloorPlan plan;
  Pose2 origin = map.origin();
  // The crop's origin: its first cell's lower-left corner, in the map's frame.
  const Vector2 half = map.origin().ToTransform().linear() * Vector2(0.5 * r, 0.5 * r);
  origin.x = corner.x() - half.x();
  origin.y = corner.y() - half.y();
  plan.truth = grid::OccupancyGrid(cw, ch, r, origin, grid::kOccupiedValue);
  plan.labels.assign(static_cast<size_t>(plan.truth.cell_count()), kPlanOutside);
  plan.between_rooms.assign(plan.labels.size(), 0);  // a real map has no drawn doorways
  std::vector<size_t> leaf;
  std::vector<uint8_t> is_leaf(static_cast<size_t>(map.cell_count()), 0);
  for (size_t i : doorway.leaf_cells) is_leaf[i] = 1;
  for (int y = 0; y < ch; ++y) {
    for (int x = 0; x < cw; ++x) {
      const size_t i = static_cast<size_t>(y + y0) * w + (x + x0);
      const size_t j = static_cast<size_t>(y) * cw + x;
      const grid::CellState state = map.StateAt(x + x0, y + y0);
      int32_t& label = plan.labels[j];
      if (state == grid::CellState::kFree) {
        label = segmentation.labels[i] == doorway.room ? 0 : kPlanCorridor;
        plan.truth.at(x, y) = grid::kFreeValue;
      } else if (state == grid::CellState::kOccupied) {
        label = kPlanWall;
      } else {
        label = building.empty() || building[i] ? kPlanUnknown : kPlanUnknownOutside;
        plan.truth.at(x, y) = grid::kUnknownValue;
      }
      if (is_leaf[i]) leaf.push_back(j);
    }
  }
  PlanDoor door;
  door.jamb_a = doorway.jamb_a;
  door.jamb_b = doorway.jamb_b;
  door.into_room = doorway.into_room;
  door.room = 0;
  door.leaf_cells = std::move(leaf);
  plan.doors.push_back(std::move(door));
  plan.rooms = 1;
  return plan;
}

}  // namespace fleetmap::bench
