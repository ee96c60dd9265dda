#include "bench/extrapolation/floor_plan_experiment.hpp"

#include <algorithm>
#include <filesystem>

#include "bench/extrapolation/floor_plan.hpp"
#include "common/core/file_io.hpp"
#include "common/extrapolation/entities_json.hpp"
#include "common/extrapolation/predicted_free_grid.hpp"
#include "common/grid/map_io.hpp"
#include "common/sim/random.hpp"

namespace fleetmap::bench {

StatusOr<std::vector<PlanDoorResult>> RunFloorPlanExperiment(
    const FloorPlanExperimentOptions& options) {
  FloorPlanOptions plan_options;
  plan_options.resolution = options.resolution;
  plan_options.unexplored_room_probability = options.unexplored_room_probability;
  FLEETMAP_ASSIGN_OR_RETURN(const FloorPlan plan, GenerateFloorPlan(plan_options, options.seed));
  return RunHiddenRoomExperiment(plan, options);
}

StatusOr<std::vector<PlanDoorResult>> RunHiddenRoomExperiment(
    const FloorPlan& plan, const FloorPlanExperimentOptions& options) {
  sim::Random random(options.seed * 7919u + 3u);
  const grid::OccupancyGrid& truth = plan.truth;
  std::vector<PlanDoorResult> results;
  for (const PlanDoor& door : plan.doors) {
    for (const bool swapped : {false, true}) {
      const HiddenRoomScene hidden = HideRoom(plan, door, swapped, options.dropout, &random);
      PlanDoorResult result;
      result.plan_seed = options.seed;
      result.room = door.room;
      result.swapped = swapped;
      result.width = (door.jamb_b - door.jamb_a).norm();
      result.leaf_on_corridor_face = door.leaf_on_corridor_face;
      result.end_room = door.end_room;
      result.second_doorway = door.second_doorway;
      result.cell_area = truth.resolution() * truth.resolution();
      const Point2 centre = hidden.door.center();
      int64_t near_room = 0;
      for (int y = 0; y < truth.height(); ++y) {
        for (int x = 0; x < truth.width(); ++x) {
          const size_t i = static_cast<size_t>(y) * truth.width() + x;
          near_room += plan.labels[i] == door.room && !plan.between_rooms[i] &&
                       (truth.CellCenter(x, y) - centre).norm() <= options.recall_radius;
        }
      }
      scene::Entities entities;
      entities.doors.push_back(hidden.door);
      for (const scene::DoorEntity& other : hidden.other_doors) entities.doors.push_back(other);
      if (!options.example_dir.empty() && results.empty()) {
        const std::string& dir = options.example_dir;
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        if (ec) return InvalidArgumentError(dir + ": cannot create the directory");
        FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(hidden.local, dir + "/local.yaml"));
        FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(truth, dir + "/truth.yaml"));
        FLEETMAP_RETURN_IF_ERROR(
            WriteFileAtomically(dir + "/entities.json", extrapolation::EntitiesToJson(entities)));
      }
      for (double p_th : options.p_th) {
        extrapolation::ExtrapolationOptions settings = options.extrapolation;
        settings.p_th = p_th;
        FLEETMAP_ASSIGN_OR_RETURN(const extrapolation::ExtrapolationResult predicted,
                                  extrapolation::Extrapolate(hidden.local, entities, settings));
        PlanDoorScore score;
        score.near_room = near_room;
        for (const scene::Submap& s : predicted.graph.submaps) {
          // The hidden door's prediction only (the other closed doors predict their own rooms).
          if (s.kind != scene::SubmapKind::kPredictedDoor ||
              std::find(s.entity_ids.begin(), s.entity_ids.end(), hidden.door.id) ==
                  s.entity_ids.end()) {
            continue;
          }
          const grid::OccupancyGrid in_map = extrapolation::SubmapGridInMapFrame(s);
          for (int y = 0; y < in_map.height(); ++y) {
            for (int x = 0; x < in_map.width(); ++x) {
              if (in_map.StateAt(x, y) != grid::CellState::kFree) continue;
              const Point2 c = in_map.CellCenter(x, y);
              const std::optional<grid::CellIndex> cell = truth.CellAt(c);
              const size_t i =
                  cell ? static_cast<size_t>(cell->y) * truth.width() + cell->x : size_t{0};
              const int32_t label = cell ? plan.labels[i] : kPlanOutside;
              if (cell && plan.between_rooms[i]) {
                ++score.unscored;
              } else if (label == door.room) {
                ++score.true_free;
                score.near_true += (c - centre).norm() <= options.recall_radius;
              } else if (label == kPlanUnknown) {
                ++score.unscored;
              } else {
                ++score.false_free;
                score.outside_building += label == kPlanOutside || label == kPlanUnknownOutside;
                score.unknown_outside += label == kPlanUnknownOutside;
              }
              score.on_observed +=
                  cell && hidden.local.StateAt(cell->x, cell->y) == grid::CellState::kFree;
            }
          }
        }
        result.scores.push_back(score);
      }
      results.push_back(std::move(result));
    }
  }
  return results;
}

}  // namespace fleetmap::bench
