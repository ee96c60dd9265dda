#include "common/sim/mapping_sessions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "common/sim/random.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::sim {
namespace {

// Every truth cell within `radius` of `centre` is free (and inside the grid).
bool DiscFree(const grid::OccupancyGrid& truth, const Point2& centre, double radius) {
  const double res = truth.resolution();
  const int x0 = static_cast<int>(std::floor((centre.x() - radius) / res));
  const int x1 = static_cast<int>(std::floor((centre.x() + radius) / res));
  const int y0 = static_cast<int>(std::floor((centre.y() - radius) / res));
  const int y1 = static_cast<int>(std::floor((centre.y() + radius) / res));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (!truth.Contains(x, y)) return false;
      if ((truth.CellCenter(x, y) - centre).norm() > radius) continue;
      if (truth.at(x, y) != grid::kFreeValue) return false;
    }
  }
  return true;
}

Status CheckPlanOptions(const SessionPlanOptions& o) {
  const int objects = static_cast<int>(o.shapes.size());
  if (objects < 1) return InvalidArgumentError("session plan: no objects (shapes is empty)");
  if (o.sessions < 2) return InvalidArgumentError("session plan: sessions must be >= 2");
  if (o.max_present < 1 || o.max_present > objects) {
    return InvalidArgumentError("session plan: max_present must be in [1, number of objects]");
  }
  if (o.min_present < 1 || o.min_present > o.max_present) {
    return InvalidArgumentError("session plan: min_present must be in [1, max_present]");
  }
  if (o.min_sessions_per_object < 1 || o.min_sessions_per_object > o.sessions) {
    return InvalidArgumentError("session plan: min_sessions_per_object must be in [1, sessions]");
  }
  if (!(o.clearance >= 0.0) || !(o.start_clearance >= 0.0)) {
    return InvalidArgumentError("session plan: clearances must be >= 0");
  }
  return Status::Ok();
}

}  // namespace

ExplorationOptions MappingSessionOptions::DefaultExploration() {
  ExplorationOptions options;
  options.error.enabled = false;
  return options;
}

StatusOr<std::vector<std::vector<MovableObject>>> PlanSessions(const grid::OccupancyGrid& truth,
                                                               const Pose2& start,
                                                               const SessionPlanOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(CheckPlanOptions(options));
  Random random(options.seed);
  const int objects = static_cast<int>(options.shapes.size());
  // Who is present in each session: random subsets until every object is seen often enough.
  std::vector<std::vector<int>> present;
  constexpr int kPresenceAttempts = 1000;
  for (int attempt = 0;; ++attempt) {
    if (attempt == kPresenceAttempts) {
      return InvalidArgumentError(
          "session plan: cannot show every object in min_sessions_per_object sessions");
    }
    present.assign(options.sessions, {});
    std::vector<int> seen(objects, 0);
    for (int t = 0; t < options.sessions; ++t) {
      const int count = random.UniformInt(options.min_present, options.max_present);
      std::vector<int> order(objects);
      for (int i = 0; i < objects; ++i) order[i] = i;
      for (int i = 0; i < count; ++i) std::swap(order[i], order[random.UniformInt(i, objects - 1)]);
      present[t].assign(order.begin(), order.begin() + count);
      std::sort(present[t].begin(), present[t].end());
      for (int id : present[t]) ++seen[id];
    }
    if (*std::min_element(seen.begin(), seen.end()) >= options.min_sessions_per_object) break;
  }
  // Where: uniform poses with free space around, away from the start and from each other.
  const double size_x = truth.width() * truth.resolution();
  const double size_y = truth.height() * truth.resolution();
  std::vector<std::vector<MovableObject>> plan(options.sessions);
  constexpr int kPoseAttempts = 20000;
  for (int t = 0; t < options.sessions; ++t) {
    for (int id : present[t]) {
      const MovableShape shape = options.shapes[id];
      const double radius = MovableShapeRadius(shape);
      bool placed = false;
      for (int attempt = 0; attempt < kPoseAttempts && !placed; ++attempt) {
        const Pose2 pose{truth.origin().x + random.Uniform(0.0, size_x),
                         truth.origin().y + random.Uniform(0.0, size_y),
                         random.Uniform(-std::numbers::pi, std::numbers::pi)};
        if ((pose.translation() - start.translation()).norm() < radius + options.start_clearance) {
          continue;
        }
        bool apart = true;
        for (const MovableObject& other : plan[t]) {
          apart = apart && (pose.translation() - other.pose.translation()).norm() >=
                               radius + MovableShapeRadius(other.shape) + options.clearance;
        }
        if (!apart || !DiscFree(truth, pose.translation(), radius + options.clearance)) continue;
        plan[t].push_back({id, shape, pose});
        placed = true;
      }
      if (!placed) {
        return InvalidArgumentError("session plan: no free place for object " + std::to_string(id) +
                                    " in session " + std::to_string(t));
      }
    }
  }
  return plan;
}

StatusOr<std::vector<MappedSession>> MapSessions(
    const Terrain& base, const std::vector<std::vector<MovableObject>>& plan,
    const MappingSessionOptions& options) {
  std::vector<MappedSession> sessions;
  for (size_t t = 0; t < plan.size(); ++t) {
    MappedSession session;
    session.objects = plan[t];
    FLEETMAP_ASSIGN_OR_RETURN(
        session.truth, RasterizeTerrain(WithMovableObjects(base, plan[t]), options.resolution));
    ExplorationOptions exploration = options.exploration;
    exploration.seed = options.exploration.seed + static_cast<uint32_t>(t);
    FLEETMAP_ASSIGN_OR_RETURN(const ExplorationSimulator simulator,
                              ExplorationSimulator::Create(exploration));
    FLEETMAP_ASSIGN_OR_RETURN(ExplorationResult result, simulator.Run(session.truth, base.start));
    session.map = std::move(result.map);
    sessions.push_back(std::move(session));
  }
  return sessions;
}

Terrain LabTerrain(double size) {
  Terrain terrain;
  terrain.kind = TerrainKind::kOffice;
  terrain.size = size;
  const double h = 0.1;  // half the boundary's thickness, inside the square
  const Point2 corners[4] = {{h, h}, {size - h, h}, {size - h, size - h}, {h, size - h}};
  for (int i = 0; i < 4; ++i) {
    Wall wall;
    wall.a = corners[i];
    wall.b = corners[(i + 1) % 4];
    wall.thickness = 0.2;
    wall.kind = ObstacleKind::kBoundary;
    terrain.walls.push_back(wall);
  }
  // Two cabinets against the walls: static structure the differencing must leave alone.
  const double w = 0.5;
  terrain.polygons.push_back({{{size * 0.4, 0.2},
                               {size * 0.4 + 1.2, 0.2},
                               {size * 0.4 + 1.2, 0.2 + w},
                               {size * 0.4, 0.2 + w}},
                              ObstacleKind::kFurniture,
                              false});
  terrain.polygons.push_back({{{size - 0.2 - w, size * 0.5},
                               {size - 0.2, size * 0.5},
                               {size - 0.2, size * 0.5 + 1.6},
                               {size - 0.2 - w, size * 0.5 + 1.6}},
                              ObstacleKind::kFurniture,
                              false});
  terrain.start = {1.0, 1.0, std::numbers::pi / 4.0};
  return terrain;
}

}  // namespace fleetmap::sim
