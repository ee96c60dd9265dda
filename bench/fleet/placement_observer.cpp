#include "bench/fleet/placement_observer.hpp"

#include <cmath>
#include <optional>

#include "common/transport/topics.hpp"
#include "common/vector_map/rasterizer.hpp"

namespace fleetmap::bench {
namespace {

// Coarser than the maps (0.05 m): the share of map two robots have in common does not need
// their cells, and the observer shares the machine with the fleet it watches.
constexpr double kCoverageResolution = 0.1;
constexpr double kCheckPeriodS = 1.0;

}  // namespace

StatusOr<std::unique_ptr<PlacementObserver>> PlacementObserver::Create(
    transport::Participant& participant, std::shared_ptr<WakeUp> wake_up,
    std::vector<Pose2> sim_frames, double size) {
  std::unique_ptr<PlacementObserver> observer(new PlacementObserver());
  FLEETMAP_ASSIGN_OR_RETURN(observer->frames_,
                            transport::RobotFrameReader::Create(participant, wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(
      observer->tiles_,
      transport::VectorTileReader::Create(participant, transport::kRobotTilesTopic, wake_up));
  const int cells = static_cast<int>(std::ceil(size / kCoverageResolution));
  observer->coverage_ = grid::OccupancyGrid(cells, cells, kCoverageResolution);
  for (size_t i = 0; i < sim_frames.size(); ++i) {
    observer->robots_["robot" + std::to_string(i)].world_from_map = sim_frames[i];
  }
  return observer;
}

PlacementObserver::~PlacementObserver() {
  frames_.reset();
  tiles_.reset();
}

RobotPlacement& PlacementObserver::PlacementOf(const std::string& robot, FleetRunResult* result) {
  std::optional<RobotPlacement>& placement = result->robots[robot].placement;
  if (!placement) {
    placement.emplace();
    const auto known = robots_.find(robot);
    if (known != robots_.end()) placement->true_world_from_map = known->second.world_from_map;
  }
  return *placement;
}

void PlacementObserver::Joined(const std::string& robot, double now_s, FleetRunResult* result) {
  RobotPlacement& placement = PlacementOf(robot, result);
  if (!placement.joined_s) placement.joined_s = now_s;
}

void PlacementObserver::Poll(double now_s, FleetRunResult* result) {
  if (finished_) return;
  for (const transport::RobotFrameEvent& event : frames_->Drain()) {
    if (event.kind != transport::RobotFrameEvent::Kind::kSample) continue;
    const transport::RobotFrameMessage& frame = event.message;
    RobotPlacement& placement = PlacementOf(frame.robot.value, result);
    placement.state = RobotFrameStateName(frame.state);
    placement.fleet_from_map = frame.fleet_from_map;
    placement.confidence = frame.confidence;
    placement.placements = frame.placements;
    placement.placed_against = frame.placed_against;
    if (frame.placed() && !placement.placed_s) placement.placed_s = now_s;
    if (frame.state == transport::RobotFrameMessage::State::kAnchor) {
      result->anchor = frame.robot.value;
    }
  }
  for (transport::TileEvent& event : tiles_->Drain()) {
    const auto robot = robots_.find(event.tile.robot_id.value);
    if (robot == robots_.end()) continue;
    if (event.kind == transport::TileEvent::Kind::kTile) {
      robot->second.tiles[event.tile.tile] = std::move(event.tile.map);
      robot->second.changed = true;
    } else if (event.kind == transport::TileEvent::Kind::kRemoved) {
      robot->second.tiles.erase(event.tile.tile);
      robot->second.changed = true;
    }
  }
  if (now_s >= next_check_s_) {
    CheckCoverage(now_s, result);
    next_check_s_ = now_s + kCheckPeriodS;
  }
}

void PlacementObserver::CheckCoverage(double now_s, FleetRunResult* result) {
  const vector_map::Rasterizer rasterizer;
  for (auto& [name, robot] : robots_) {
    if (!robot.changed) continue;
    robot.changed = false;
    vector_map::VectorMap merged;
    for (const auto& [tile, map] : robot.tiles) merged.Append(map);
    const auto raster = rasterizer.Rasterize(
        vector_map::Transformed(merged, robot.world_from_map.ToTransform(), "world"), coverage_);
    if (!raster.ok()) continue;
    robot.known.assign(raster->cell_count(), false);
    robot.known_cells = 0;
    robot.known_sum_world = Point2::Zero();
    for (int y = 0; y < raster->height(); ++y) {
      for (int x = 0; x < raster->width(); ++x) {
        if (raster->StateAt(x, y) == grid::CellState::kUnknown) continue;
        robot.known[static_cast<size_t>(y) * raster->width() + x] = true;
        ++robot.known_cells;
        robot.known_sum_world += raster->CellCenter(x, y);
      }
    }
  }
  // How many placed robots know each cell.
  const auto placed = [&](const std::string& name) {
    const auto found = result->robots.find(name);
    return found != result->robots.end() && found->second.placement &&
           found->second.placement->placed_s.has_value();
  };
  std::vector<int> placed_known(coverage_.cell_count(), 0);
  for (const auto& [name, robot] : robots_) {
    if (!placed(name)) continue;
    for (size_t i = 0; i < robot.known.size(); ++i) placed_known[i] += robot.known[i];
  }
  for (const auto& [name, robot] : robots_) {
    if (robot.known_cells == 0 || name == result->anchor) continue;
    RobotPlacement& placement = PlacementOf(name, result);
    if (placement.shared_s) continue;
    // Shared with the other placed robots: a placed robot's own cells do not count.
    const int self = placed(name) ? 1 : 0;
    int64_t shared = 0;
    for (size_t i = 0; i < robot.known.size(); ++i) {
      shared += robot.known[i] && placed_known[i] - self > 0;
    }
    placement.shared_fraction = static_cast<double>(shared) / robot.known_cells;
    if (placement.shared_fraction >= kSharedFraction) placement.shared_s = now_s;
  }
}

void PlacementObserver::Finish(double now_s, FleetRunResult* result) {
  if (result->anchor.empty()) {
    // The anchor's state can turn to "given" at once (the server notes the placement it already
    // has when the robot's status comes after its tiles): then the first robot placed at the
    // identity is the anchor.
    std::optional<double> first;
    for (const auto& [name, robot] : result->robots) {
      if (!robot.placement || !robot.placement->placed_s || robot.placement->state != "given" ||
          !(robot.placement->fleet_from_map == Pose2{})) {
        continue;
      }
      if (!first || *robot.placement->placed_s < *first) {
        first = robot.placement->placed_s;
        result->anchor = name;
      }
    }
  }
  CheckCoverage(now_s, result);
  finished_ = true;
  for (const auto& [name, robot] : robots_) {
    if (robot.known_cells == 0) continue;
    RobotPlacement& placement = PlacementOf(name, result);
    placement.known_cells = robot.known_cells;
    placement.known_centroid = robot.world_from_map.ToTransform().inverse() *
                               Point2(robot.known_sum_world / robot.known_cells);
  }
}

}  // namespace fleetmap::bench
