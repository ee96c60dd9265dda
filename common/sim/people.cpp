#include "common/sim/people.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace fleetmap::sim {
namespace {

bool FreeAt(const grid::OccupancyGrid& truth, const Point2& p) {
  const auto cell = truth.CellAt(p);
  return cell && truth.StateAt(cell->x, cell->y) == grid::CellState::kFree;
}

// True if every cell on the straight line from a to b is free (half-cell steps).
bool Clear(const grid::OccupancyGrid& truth, const Point2& a, const Point2& b) {
  const double length = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.5 * truth.resolution()))));
  for (int i = 0; i <= steps; ++i) {
    if (!FreeAt(truth, a + (b - a) * (static_cast<double>(i) / steps))) return false;
  }
  return true;
}

// Samples a polyline at constant speed every `period` seconds.
std::vector<WalkSample> Sample(const std::vector<Point2>& path, double speed, double period) {
  std::vector<WalkSample> samples;
  const double step = speed * period;
  double carried = 0.0;  // distance already walked past the current vertex
  double stamp = 0.0;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const Vector2 d = path[i + 1] - path[i];
    const double length = d.norm();
    if (length < 1e-9) continue;
    const double heading = std::atan2(d.y(), d.x());
    for (double s = carried; s < length; s += step) {
      samples.push_back({stamp, path[i] + d * (s / length), heading});
      stamp += period;
    }
    carried = std::fmod(carried - length, step);
    if (carried < 0.0) carried += step;
  }
  return samples;
}

}  // namespace

std::vector<PersonWalk> GenerateWalks(const IndoorScene& scene, const grid::OccupancyGrid& truth,
                                      int count, const WalkOptions& options, Random* random) {
  std::vector<PersonWalk> walks;
  const double x_lo = scene.corridor_min.x() + 0.5, x_hi = scene.corridor_max.x() - 0.5;
  for (int k = 0; k < count; ++k) {
    PersonWalk walk;
    walk.id = "person_" + std::to_string(k + 1);
    walk.dominant_side = random->Bernoulli(0.5) ? 1 : -1;
    const double direction = random->Bernoulli(0.5) ? 1.0 : -1.0;
    const double length = random->Uniform(options.min_length, options.max_length);
    double x0 = random->Uniform(x_lo, x_hi);
    double x1 = std::clamp(x0 + direction * length, x_lo, x_hi);
    if (std::abs(x1 - x0) < 2.0) {
      x1 = std::clamp(x0 - direction * length, x_lo, x_hi);
    }
    const double heading_sign = x1 > x0 ? 1.0 : -1.0;
    // Right of a walker heading +x is -y. People keep 0.35-0.5 m from the wall on their dominant
    // side.
    const bool near_low_wall = (walk.dominant_side == 1) == (heading_sign > 0.0);
    const double gap = random->Uniform(0.35, 0.5);
    const double y = near_low_wall ? scene.corridor_min.y() + gap : scene.corridor_max.y() - gap;
    std::vector<Point2> path = {Point2(x0, y), Point2(x1, y)};
    if (random->Bernoulli(options.turn_in_probability)) {
      // The first open door ahead along the walk: go through it into the room.
      const SceneDoor* best = nullptr;
      for (const SceneDoor& door : scene.doors) {
        if (!door.open) continue;
        const double ahead = (door.center().x() - x0) * heading_sign;
        const double span = std::abs(x1 - x0);
        if (ahead < 1.0 || ahead > span) continue;
        if (best == nullptr || ahead < (best->center().x() - x0) * heading_sign) best = &door;
      }
      if (best != nullptr) {
        const Point2 in_corridor(best->center().x() - heading_sign * 0.5, y);
        const Point2 doorway = best->center() - 0.3 * best->room_side;
        Point2 inside = best->center() + random->Uniform(1.2, 2.2) * best->room_side;
        while ((inside - best->center()).norm() > 0.5 && !Clear(truth, best->center(), inside)) {
          inside -= 0.1 * best->room_side;
        }
        path = {Point2(x0, y), in_corridor, doorway, best->center(), inside};
      }
    }
    walk.samples =
        Sample(path, random->Uniform(options.min_speed, options.max_speed), options.period);
    if (walk.samples.size() >= 2) walks.push_back(std::move(walk));
  }
  return walks;
}

std::optional<ObservedWalk> ObserveWalk(const PersonWalk& walk, const grid::OccupancyGrid& truth,
                                        const Point2& robot, double range, double position_noise,
                                        Random* random) {
  auto visible = [&](const WalkSample& s) {
    return (s.position - robot).norm() <= range && Clear(truth, robot, s.position);
  };
  size_t first = 0;
  while (first < walk.samples.size() && !visible(walk.samples[first])) ++first;
  size_t last = first;
  while (last + 1 < walk.samples.size() && visible(walk.samples[last + 1])) ++last;
  if (first >= walk.samples.size() || last - first + 1 < 2) return std::nullopt;
  ObservedWalk observed;
  observed.id = walk.id;
  observed.dominant_side = walk.dominant_side;
  observed.entered_view = first > 0;
  observed.left_view = last + 1 < walk.samples.size();
  for (size_t i = first; i <= last; ++i) {
    WalkSample s = walk.samples[i];
    s.position +=
        Point2(random->Gaussian(0.0, position_noise), random->Gaussian(0.0, position_noise));
    s.heading += random->Gaussian(0.0, 0.05);
    observed.points.push_back(s);
  }
  return observed;
}

}  // namespace fleetmap::sim
