#include "bench/extrapolation/extrapolation_experiment.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>

#include "common/core/file_io.hpp"
#include "common/extrapolation/door_detector.hpp"
#include "common/extrapolation/entities_json.hpp"
#include "common/extrapolation/extrapolator.hpp"
#include "common/extrapolation/map_queries.hpp"
#include "common/extrapolation/ply_reader.hpp"
#include "common/extrapolation/predicted_free_grid.hpp"
#include "common/extrapolation/stairs_detector.hpp"
#include "common/grid/map_io.hpp"
#include "common/sim/depth_sensor.hpp"
#include "common/sim/indoor_scene_generator.hpp"
#include "common/sim/laser_scanner.hpp"
#include "common/sim/occupancy_mapper.hpp"
#include "common/sim/people.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::bench {
namespace {

namespace ex = extrapolation;

constexpr double kDoorMatch = 0.3;       // m between detected and true door centres
constexpr double kDoorWidthMatch = 0.2;  // m
constexpr double kStairsMatch = 0.3;     // m between feet
constexpr double kStairsAngleMatch = 10.0 * std::numbers::pi / 180.0;
constexpr double kStairsWidthMatch = 0.25;  // m

ex::PointCloud ToCloud(const std::vector<Eigen::Vector3d>& points) {
  return ex::PointCloud(points.begin(), points.end());
}

bool SameDoor(const scene::DoorEntity& detected, const sim::SceneDoor& truth) {
  return (detected.center() - truth.center()).norm() < kDoorMatch &&
         std::abs(detected.width() - truth.width()) < kDoorWidthMatch;
}

}  // namespace

StatusOr<ExtrapolationSceneResult> RunExtrapolationScene(const ExtrapolationSceneOptions& options) {
  ExtrapolationSceneResult result;
  result.seed = options.seed;
  sim::IndoorSceneOptions scene_options;
  scene_options.closed_door_probability = options.closed_door_probability;
  const sim::IndoorScene scene = sim::GenerateIndoorScene(scene_options, options.seed);
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid as_set,
                            sim::RasterizeGroundFloor(scene, options.resolution, true));
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid truth,
                            sim::RasterizeGroundFloor(scene, options.resolution, false));
  FLEETMAP_ASSIGN_OR_RETURN(const grid::OccupancyGrid upper,
                            sim::RasterizeUpperFloor(scene, options.resolution));
  sim::Random random(options.seed * 7919u + 17u);

  // The local map: the robot drives the corridor's centre line from the west end to x_r.
  sim::LaserOptions laser;
  laser.field_of_view = 2.0 * std::numbers::pi;
  laser.angular_step = 0.5 * std::numbers::pi / 180.0;
  laser.max_range = options.laser_range;
  FLEETMAP_ASSIGN_OR_RETURN(const sim::LaserScanner scanner, sim::LaserScanner::Create(laser));
  FLEETMAP_ASSIGN_OR_RETURN(sim::OccupancyMapper mapper,
                            sim::OccupancyMapper::Create(as_set.width(), as_set.height(),
                                                         as_set.resolution(), as_set.origin(), {}));
  const double yc = 0.5 * (scene.corridor_min.y() + scene.corridor_max.y());
  const double x_start = scene.corridor_min.x() + 0.6;
  const double x_end = scene.corridor_max.x() - 0.6;
  const double x_robot = random.Uniform(x_start + 0.45 * (x_end - x_start), x_end - 1.0);
  for (double x = x_start; x <= x_robot + 1e-9; x += 0.5) {
    const Pose2 pose{x, yc, 0.0};
    mapper.Integrate(scanner.Scan(as_set, pose, &random), pose);
  }
  const grid::OccupancyGrid local = mapper.ToGrid();
  result.cell_area = local.resolution() * local.resolution();
  result.observed_free_cells = local.CountStates().free;

  FLEETMAP_ASSIGN_OR_RETURN(const sim::DepthSensor camera, sim::DepthSensor::Create({}));
  const std::vector<sim::Box3> boxes = sim::SceneBoxes(scene);
  scene::Entities entities;
  ex::PointCloud all_views;  // for example_dir
  auto capture = [&](const sim::CameraPose& pose) {
    ex::PointCloud cloud = ToCloud(camera.Capture(boxes, pose, &random));
    if (!options.example_dir.empty()) all_views.insert(all_views.end(), cloud.begin(), cloud.end());
    return cloud;
  };

  // Doors: one view of each closed door whose leaf the robot mapped.
  auto add_door = [&](const scene::DoorEntity& door) {
    for (const scene::DoorEntity& known : entities.doors) {
      if ((known.center() - door.center()).norm() < kDoorMatch) return;
    }
    entities.doors.push_back(door);
    entities.doors.back().id = "door_" + std::to_string(entities.doors.size());
  };
  for (const sim::SceneDoor& door : scene.doors) {
    if (door.open) continue;
    // The robot mapped the leaf's corridor face (the laser marks the first cell it hits).
    bool mapped = false;
    for (double t = 0.0; t <= 0.1; t += 0.5 * local.resolution()) {
      mapped |=
          ex::StateAtPoint(local, door.center() - t * door.room_side) == grid::CellState::kOccupied;
    }
    if (!mapped) continue;
    ++result.closed_doors_viewed;
    const double along = random.Uniform(1.6, 2.0);
    const bool from_west = door.center().x() - along >= x_start;
    const Point2 eye(door.center().x() + (from_west ? -along : along),
                     yc + random.Uniform(-0.15, 0.15));
    const Vector2 look = door.center() - eye;
    sim::CameraPose pose;
    pose.pose =
        Pose2{eye.x(), eye.y(), std::atan2(look.y(), look.x()) + random.Gaussian(0.0, 0.05)};
    const std::vector<ex::DetectedDoor> found = ex::DetectDoors(capture(pose), eye);
    bool detected = false;
    for (const ex::DetectedDoor& d : found) {
      // A false positive is where no door is; a door found too narrow (partly hidden) is not one.
      bool at_a_door = false;
      for (const sim::SceneDoor& other : scene.doors) {
        at_a_door |= (d.entity.center() - other.center()).norm() < kDoorMatch;
      }
      if (!at_a_door) {
        ++result.door_false_positives;
        continue;
      }
      if (SameDoor(d.entity, door) && !detected) {
        detected = true;
        ++result.doors_detected;
        result.hinges_correct += (d.entity.hinge - door.hinge).norm() < kDoorMatch;
      }
      add_door(d.entity);
    }
  }

  // Stairs: views from 1.8-3 m before the foot.
  for (int v = 0; v < options.stairs_views; ++v) {
    ++result.stairs_views;
    const sim::SceneStairs& stairs = scene.stairs;
    sim::CameraPose pose;
    pose.pose = Pose2{stairs.foot.x() - random.Uniform(1.8, 3.0), yc + random.Uniform(-0.2, 0.2),
                      random.Gaussian(0.0, 0.1)};
    bool detected = false;
    for (const ex::DetectedStairs& s : ex::DetectStairs(capture(pose))) {
      const bool match = (s.entity.position - stairs.foot).norm() < kStairsMatch &&
                         s.entity.ascending.dot(stairs.ascending) > std::cos(kStairsAngleMatch) &&
                         std::abs(s.entity.step_width - stairs.width) < kStairsWidthMatch;
      if (!match) {
        ++result.stairs_false_positives;
        continue;
      }
      if (!detected) ++result.stairs_detected;
      detected = true;
      if (entities.stairs.empty()) {
        entities.stairs.push_back(s.entity);
        entities.stairs.back().id = "stairs_1";
      }
    }
  }

  // People, seen from where the robot stopped.
  const std::vector<sim::PersonWalk> walks =
      sim::GenerateWalks(scene, as_set, options.people, {}, &random);
  const Point2 robot(x_robot, yc);
  for (const sim::PersonWalk& walk : walks) {
    const std::optional<sim::ObservedWalk> observed =
        sim::ObserveWalk(walk, as_set, robot, options.person_view_range, 0.03, &random);
    if (!observed) continue;
    scene::PersonTrack track;
    track.id = observed->id;
    track.entered_view = observed->entered_view;
    track.left_view = observed->left_view;
    for (const sim::WalkSample& s : observed->points) {
      track.points.push_back({s.stamp, s.position, s.heading});
    }
    ++result.tracks;
    const std::optional<int> side = ex::InferDominantSide(local, track, 2.0);
    result.dominant_sides_correct += side && *side == observed->dominant_side;
    entities.people.push_back(std::move(track));
  }

  if (!options.example_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.example_dir, ec);
    if (ec) return InvalidArgumentError(options.example_dir + ": cannot create the directory");
    const std::string& dir = options.example_dir;
    FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(local, dir + "/local.yaml"));
    FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(truth, dir + "/truth.yaml"));
    FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(upper, dir + "/upper.yaml"));
    FLEETMAP_RETURN_IF_ERROR(ex::WritePly(all_views, dir + "/views.ply"));
    FLEETMAP_RETURN_IF_ERROR(
        WriteFileAtomically(dir + "/entities.json", ex::EntitiesToJson(entities)));
  }
  for (double p_th : options.p_th) {
    ex::ExtrapolationOptions extrapolation = options.extrapolation;
    extrapolation.p_th = p_th;
    FLEETMAP_ASSIGN_OR_RETURN(ex::ExtrapolationResult predicted,
                              ex::Extrapolate(local, entities, extrapolation));
    ThresholdScores scores;
    for (const scene::Submap& s : predicted.graph.submaps) {
      if (s.kind == scene::SubmapKind::kPredictedStairs)
        scores.stairs += ex::CheckPrediction(s, upper);
      if (s.kind == scene::SubmapKind::kPredictedDoor) {
        scores.doors += ex::CheckPredictedGrid(ex::SubmapGridInMapFrame(s), truth, &local);
      }
    }
    scores.people = ex::CheckPredictedGrid(predicted.conditionally_free, truth, &local);
    scores.people_new_cells =
        scores.people.true_free + scores.people.false_free + scores.people.unobserved;
    predicted.conditionally_free.mutable_data().assign(predicted.conditionally_free.data().size(),
                                                       grid::kUnknownValue);
    scores.door_new_cells = ex::ComposeFloorGrids(local, predicted).predicted_free_cells;
    result.scores.push_back(scores);
  }
  return result;
}

}  // namespace fleetmap::bench
