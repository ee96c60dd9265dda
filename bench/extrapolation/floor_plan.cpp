#include "bench/extrapolation/floor_plan.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace fleetmap::bench {
namespace {

// An axis-aligned rectangle [x0, x1) x [y0, y1) (metres) painted with a label.
struct Rect {
  double x0, y0, x1, y1;
  int32_t label;
};

// A row of rooms along one side of the corridor: [x0, x1) spans, all of the same depth.
std::vector<std::pair<double, double>> SplitIntoRooms(double x0, double x1, double wall,
                                                      sim::Random* random) {
  std::vector<std::pair<double, double>> spans;
  double x = x0;
  while (x < x1) {
    double width = random->Uniform(2.5, 5.0);
    // The last room takes what is left rather than leave a sliver.
    if (x1 - (x + width + wall) < 2.5) width = x1 - x;
    spans.emplace_back(x, x + width);
    x += width + wall;
  }
  return spans;
}

}  // namespace

StatusOr<FloorPlan> GenerateFloorPlan(const FloorPlanOptions& options, uint32_t seed) {
  if (!(options.outside_margin >= 0.0 && options.outside_margin <= 20.0) ||
      !(options.unexplored_room_probability >= 0.0 && options.unexplored_room_probability <= 1.0)) {
    return InvalidArgumentError(
        "floor plan: outside margin outside [0, 20] m or unexplored room "
        "probability outside [0, 1]");
  }
  if (!(options.resolution >= 0.01 && options.resolution <= 0.2)) {
    return InvalidArgumentError("floor plan resolution " + std::to_string(options.resolution) +
                                " m is outside [0.01, 0.2]");
  }
  sim::Random random(seed * 2654435761u + 11u);
  const double length = random.Uniform(14.0, 26.0);
  const double exterior = random.Uniform(0.3, 0.5);
  const double interior = random.Uniform(0.15, 0.5);
  const double corridor_width = random.Uniform(1.2, 2.0);
  const double depth_low = random.Uniform(3.0, 5.5);
  const double depth_high = random.Uniform(3.0, 5.5);
  const double corridor_y0 = exterior + depth_low + interior;
  const double corridor_y1 = corridor_y0 + corridor_width;
  const double height = corridor_y1 + interior + depth_high + exterior;

  FloorPlan plan;
  std::vector<Rect> rects;  // painted in order over the building's wall
  rects.push_back({exterior, corridor_y0, length - exterior, corridor_y1, kPlanCorridor});
  struct Side {
    double y0, y1;   // the rooms' extent across the corridor
    double wall_y0;  // the corridor wall between rooms and corridor
    double wall_y1;
    double corridor_face;  // the wall's face on the corridor
    double room_face;
    Vector2 into_room;
  };
  const Side sides[2] = {
      {exterior, exterior + depth_low, exterior + depth_low, corridor_y0, corridor_y0,
       exterior + depth_low, Vector2(0, -1)},
      {corridor_y1 + interior, corridor_y1 + interior + depth_high, corridor_y1,
       corridor_y1 + interior, corridor_y1, corridor_y1 + interior, Vector2(0, 1)},
  };
  struct DoorPlan {
    double x0, x1;
    const Side* side;
    bool leaf_on_corridor_face;
    int32_t room;
    bool end_room;
  };
  std::vector<uint8_t> second_doorway;  // per room
  std::vector<DoorPlan> door_plans;
  std::vector<Rect> between_rooms;  // the open doorways between neighbouring rooms
  // A rectangle between two ordinates given in either order.
  const auto across = [](double x0, double x1, double a, double b, int32_t label) {
    return Rect{x0, std::min(a, b), x1, std::max(a, b), label};
  };
  for (const Side& side : sides) {
    const auto spans = SplitIntoRooms(exterior, length - exterior, interior, &random);
    const double full_depth = side.y1 - side.y0;
    const double sign = side.into_room.y();
    const double outer = sign < 0 ? 0.0 : height;  // the building's outline on this side
    // Most rooms reach the exterior wall; some are shallower (a bathroom, a store room), and the
    // outline steps in behind them.
    std::vector<double> depths;
    for (size_t i = 0; i < spans.size(); ++i) {
      depths.push_back(random.Bernoulli(options.shallow_room_probability)
                           ? random.Uniform(2.0, std::max(2.0, full_depth - 0.3))
                           : full_depth);
    }
    for (size_t i = 0; i < spans.size(); ++i) {
      const auto [x0, x1] = spans[i];
      const double depth = depths[i];
      const double back = side.room_face + sign * depth;
      const int32_t room = plan.rooms++;
      rects.push_back(across(x0, x1, side.room_face, back, room));
      if (depth < full_depth) {
        rects.push_back(across(x0, x1, back + sign * exterior, outer, kPlanOutside));
      }
      // A closet in a back corner of a large room, walled off, with its own open doorway: part
      // of the room behind the door, its walls unseen like the room's.
      if (x1 - x0 >= 3.0 && depth >= 3.5 && random.Bernoulli(options.closet_probability)) {
        const double cw = random.Uniform(1.2, 1.8), cd = random.Uniform(1.2, 1.8);
        const bool left = random.Bernoulli(0.5);
        const double cx0 = left ? x0 : x1 - cw;
        const double cx1 = left ? x0 + cw : x1;
        const double wx0 = left ? cx0 : cx0 - interior;
        const double wx1 = left ? cx1 + interior : cx1;
        const double front = back - sign * cd;
        rects.push_back(across(wx0, wx1, back, front - sign * interior, kPlanWall));
        rects.push_back(across(cx0, cx1, back, front, room));
        rects.push_back(across(cx0 + 0.2, cx0 + 0.9, front, front - sign * interior, room));
      }
      const double width = std::min(random.Uniform(0.8, 1.0), x1 - x0 - 0.2);
      double door_x0;
      if (random.Bernoulli(options.corner_door_probability)) {
        const double offset = random.Uniform(0.05, 0.3);
        door_x0 = random.Bernoulli(0.5) ? x0 + offset : x1 - offset - width;
      } else {
        door_x0 = random.Uniform(x0 + 0.3, std::max(x0 + 0.3, x1 - 0.3 - width));
      }
      const bool end_room = i == 0 || i + 1 == spans.size();
      door_plans.push_back(
          {door_x0, door_x0 + width, &side, random.Bernoulli(0.5), room, end_room});
      second_doorway.resize(static_cast<size_t>(room) + 2, 0);
      // A second, open doorway into the next room on this side, through the wall between them,
      // in front of any closet.
      if (i + 1 < spans.size() && random.Bernoulli(options.connecting_doorway_probability)) {
        const double w = random.Uniform(0.8, 0.9);
        const double shared = std::min(depth, depths[i + 1]);
        const double offset = random.Uniform(0.3, std::max(0.3, shared - 2.3 - w));
        const double y = side.room_face + sign * offset;
        const int32_t owner = random.Bernoulli(0.5) ? room : room + 1;
        rects.push_back(across(x1, spans[i + 1].first, y, y + sign * w, owner));
        between_rooms.push_back(rects.back());
        second_doorway[room] = second_doorway[room + 1] = 1;
        ++plan.connecting_doorways;
      }
    }
  }
  for (const DoorPlan& d : door_plans) {
    // The doorway through the corridor wall: the corridor's up to the leaf, the room's from it.
    const Side& s = *d.side;
    rects.push_back({d.x0, s.wall_y0, d.x1, s.wall_y1, d.room});
    if (!d.leaf_on_corridor_face) {
      const double y0 = std::min(s.corridor_face, s.room_face);
      const double y1 = std::max(s.corridor_face, s.room_face);
      // The recess in front of a leaf on the room's face belongs to the corridor.
      if (s.into_room.y() < 0) {
        rects.push_back({d.x0, s.room_face, d.x1, y1, kPlanCorridor});
      } else {
        rects.push_back({d.x0, y0, d.x1, s.room_face, kPlanCorridor});
      }
    }
  }

  // Drawn after the layout so that the layout's random draws, hence the plans of a seed, do not
  // depend on it.
  plan.unexplored.assign(static_cast<size_t>(plan.rooms), 0);
  for (uint8_t& u : plan.unexplored) u = random.Bernoulli(options.unexplored_room_probability);
  const double r = options.resolution;
  const double m = options.outside_margin;
  const int width_cells = static_cast<int>(std::ceil((length + 2.0 * m) / r));
  const int height_cells = static_cast<int>(std::ceil((height + 2.0 * m) / r));
  plan.truth =
      grid::OccupancyGrid(width_cells, height_cells, r, Pose2{-m, -m, 0.0}, grid::kOccupiedValue);
  plan.labels.assign(static_cast<size_t>(plan.truth.cell_count()), kPlanOutside);
  plan.between_rooms.assign(plan.labels.size(), 0);
  for (int y = 0; y < height_cells; ++y) {
    for (int x = 0; x < width_cells; ++x) {
      const Point2 c = plan.truth.CellCenter(x, y);
      int32_t label = kPlanOutside;
      if (c.x() >= 0 && c.x() < length && c.y() >= 0 && c.y() < height) label = kPlanWall;
      for (const Rect& rect : rects) {
        if (c.x() >= rect.x0 && c.x() < rect.x1 && c.y() >= rect.y0 && c.y() < rect.y1) {
          label = rect.label;
        }
      }
      plan.labels[static_cast<size_t>(y) * width_cells + x] = label;
      if (label >= kPlanCorridor) plan.truth.at(x, y) = grid::kFreeValue;
      for (const Rect& rect : between_rooms) {
        if (c.x() >= rect.x0 && c.x() < rect.x1 && c.y() >= rect.y0 && c.y() < rect.y1) {
          plan.between_rooms[static_cast<size_t>(y) * width_cells + x] = 1;
        }
      }
    }
  }

  for (const DoorPlan& d : door_plans) {
    const Side& s = *d.side;
    const double face = d.leaf_on_corridor_face ? s.corridor_face : s.room_face;
    PlanDoor door;
    door.jamb_a = Point2(d.x0, face);
    door.jamb_b = Point2(d.x1, face);
    door.into_room = s.into_room;
    door.room = d.room;
    door.leaf_on_corridor_face = d.leaf_on_corridor_face;
    door.end_room = d.end_room;
    door.second_doorway = second_doorway[d.room] != 0;
    // The leaf: the doorway's row of cells inside the wall next to the face that holds it.
    const double lo = d.leaf_on_corridor_face ? 0.0 : -r;
    for (int y = 0; y < height_cells; ++y) {
      for (int x = 0; x < width_cells; ++x) {
        const Point2 c = plan.truth.CellCenter(x, y);
        const double behind = (c.y() - face) * s.into_room.y();
        if (c.x() >= d.x0 && c.x() < d.x1 && behind > lo && behind <= lo + r) {
          door.leaf_cells.push_back(static_cast<size_t>(y) * width_cells + x);
        }
      }
    }
    plan.doors.push_back(std::move(door));
  }
  std::sort(plan.doors.begin(), plan.doors.end(),
            [](const PlanDoor& a, const PlanDoor& b) { return a.room < b.room; });
  return plan;
}

HiddenRoomScene HideRoom(const FloorPlan& plan, const PlanDoor& door, bool swap_hinge,
                         double dropout, sim::Random* random) {
  HiddenRoomScene hidden;
  const grid::OccupancyGrid& truth = plan.truth;
  const int w = truth.width(), h = truth.height();
  hidden.local = grid::OccupancyGrid(w, h, truth.resolution(), truth.origin(), grid::kUnknownValue);
  grid::OccupancyGrid& local = hidden.local;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int32_t label = plan.labels[static_cast<size_t>(y) * w + x];
      const bool unexplored = label >= 0 && static_cast<size_t>(label) < plan.unexplored.size() &&
                              plan.unexplored[static_cast<size_t>(label)];
      if (label >= kPlanCorridor && label != door.room && !unexplored) {
        local.at(x, y) = grid::kFreeValue;
      }
    }
  }
  std::vector<uint8_t> is_leaf(plan.labels.size(), 0);
  for (size_t i : door.leaf_cells) is_leaf[i] = 1;
  // The unexplored rooms' doors are closed: their leaves are seen like walls.
  std::vector<uint8_t> other_leaf(plan.labels.size(), 0);
  for (const PlanDoor& other : plan.doors) {
    if (other.room == door.room || static_cast<size_t>(other.room) >= plan.unexplored.size() ||
        !plan.unexplored[static_cast<size_t>(other.room)]) {
      continue;
    }
    for (size_t i : other.leaf_cells) other_leaf[i] = 1;
    scene::DoorEntity entity;
    entity.id = "door_room_" + std::to_string(other.room);
    entity.hinge = other.jamb_a;
    entity.latch = other.jamb_b;
    entity.opening_direction = other.into_room;
    entity.open = false;
    hidden.other_doors.push_back(std::move(entity));
  }
  // Walls are seen where the robot stood next to them.
  std::vector<size_t> faces;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (plan.labels[i] != kPlanWall && !is_leaf[i] && !other_leaf[i]) continue;
      bool seen = false;
      for (int dy = -1; dy <= 1 && !seen; ++dy) {
        for (int dx = -1; dx <= 1 && !seen; ++dx) {
          seen = truth.Contains(x + dx, y + dy) && local.at(x + dx, y + dy) == grid::kFreeValue;
        }
      }
      if (seen || is_leaf[i]) local.at(x, y) = grid::kOccupiedValue;
      if (seen && !is_leaf[i]) faces.push_back(i);
    }
  }
  // Laser dropouts: short runs of a face left unknown (glass, a dark surface, a grazing angle).
  for (size_t i : faces) {
    if (!random->Bernoulli(dropout)) continue;
    const int length = random->UniformInt(1, 4);
    const bool along_x = random->Bernoulli(0.5);
    int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    for (int k = 0; k < length && local.Contains(x, y); ++k) {
      const size_t j = static_cast<size_t>(y) * w + x;
      if (plan.labels[j] != kPlanWall || local.at(x, y) != grid::kOccupiedValue) break;
      local.at(x, y) = grid::kUnknownValue;
      (along_x ? x : y) += 1;
    }
  }
  hidden.door.id = "door_room_" + std::to_string(door.room);
  hidden.door.hinge = swap_hinge ? door.jamb_b : door.jamb_a;
  hidden.door.latch = swap_hinge ? door.jamb_a : door.jamb_b;
  hidden.door.opening_direction = door.into_room;
  hidden.door.open = false;
  return hidden;
}

}  // namespace fleetmap::bench
