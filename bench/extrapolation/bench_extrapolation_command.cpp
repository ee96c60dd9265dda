#include "bench/extrapolation/bench_extrapolation_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/extrapolation/extrapolation_experiment.hpp"
#include "bench/extrapolation/floor_plan_experiment.hpp"
#include "bench/extrapolation/room_segmentation.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"
#include "common/grid/map_io.hpp"

namespace fleetmap::bench {
namespace {

using extrapolation::PredictionCheck;

std::string Ratio(int64_t a, int64_t b) {
  return b > 0 ? Fixed(static_cast<double>(a) / b, 3) : "n/a";
}

std::string Precision(const PredictionCheck& c) {
  return c.true_free + c.false_free > 0 ? Fixed(c.precision, 3) : "n/a";
}

struct Totals {
  int closed_doors = 0, doors_detected = 0, hinges = 0, door_fp = 0;
  int stairs_views = 0, stairs_detected = 0, stairs_fp = 0;
  int tracks = 0, sides = 0;
  int64_t observed_free = 0;
  double cell_area = 0;
  std::vector<PredictionCheck> stairs, doors, people, overall;
  std::vector<int64_t> door_cells, people_cells;
  std::vector<double> gain_sum;  // sum over scenes of door cells / observed free cells
};

Totals Sum(const std::vector<ExtrapolationSceneResult>& results, size_t thresholds) {
  Totals t;
  t.stairs.resize(thresholds), t.doors.resize(thresholds), t.people.resize(thresholds);
  t.overall.resize(thresholds), t.door_cells.resize(thresholds), t.people_cells.resize(thresholds);
  t.gain_sum.resize(thresholds);
  for (const ExtrapolationSceneResult& r : results) {
    t.closed_doors += r.closed_doors_viewed, t.doors_detected += r.doors_detected;
    t.hinges += r.hinges_correct, t.door_fp += r.door_false_positives;
    t.stairs_views += r.stairs_views, t.stairs_detected += r.stairs_detected;
    t.stairs_fp += r.stairs_false_positives, t.tracks += r.tracks;
    t.sides += r.dominant_sides_correct, t.observed_free += r.observed_free_cells;
    t.cell_area = r.cell_area;
    for (size_t k = 0; k < thresholds; ++k) {
      const ThresholdScores& s = r.scores[k];
      t.stairs[k] += s.stairs, t.doors[k] += s.doors, t.people[k] += s.people;
      t.overall[k] += s.stairs, t.overall[k] += s.doors, t.overall[k] += s.people;
      t.door_cells[k] += s.door_new_cells, t.people_cells[k] += s.people_new_cells;
      if (r.observed_free_cells > 0) {
        t.gain_sum[k] += static_cast<double>(s.door_new_cells) / r.observed_free_cells;
      }
    }
  }
  return t;
}

std::string Report(const BenchExtrapolationOptions& options,
                   const std::vector<ExtrapolationSceneResult>& results, double seconds) {
  const size_t n = options.p_th.size();
  const Totals t = Sum(results, n);
  std::ostringstream md;
  md << "# Map extrapolation on simulated indoor scenes\n\n"
     << "Command: `fleetmap bench extrapolation --scenes " << options.scenes << " --seed "
     << options.seed << "`  \nMachine: " << MachineDescription() << ", Release build.  \n"
     << "Wall time: " << Fixed(seconds, 1) << " s for " << results.size() << " scenes.\n\n";
  md << "## Detection recall (one RGB-D view per closed door, " << results.front().stairs_views
     << " per flight of stairs)\n\n"
     << "| entity | detected / views | recall | paper | false positives |\n|---|---|---|---|---|\n"
     << "| stairs | " << t.stairs_detected << " / " << t.stairs_views << " | "
     << Ratio(t.stairs_detected, t.stairs_views) << " | 0.95 | " << t.stairs_fp << " |\n"
     << "| doors (closed) | " << t.doors_detected << " / " << t.closed_doors << " | "
     << Ratio(t.doors_detected, t.closed_doors) << " | 0.67 | " << t.door_fp << " |\n\n"
     << "Hinge side right for " << t.hinges << " of " << t.doors_detected
     << " detected doors; dominant side inferred right for " << t.sides << " of " << t.tracks
     << " people's tracks.\n\n";
  md << "## Free-space precision TP / (TP + FP)\n\n| class |";
  for (double p : options.p_th) md << " p_th " << Fixed(p, 2) << " |";
  md << " paper (0.5 / 0.6 / 0.7) |\n|---|";
  for (size_t k = 0; k < n; ++k) md << "---|";
  md << "---|\n";
  auto row = [&](const char* name, const std::vector<PredictionCheck>& checks, const char* paper) {
    md << "| " << name << " |";
    for (const PredictionCheck& c : checks) {
      md << " " << Precision(c) << " (" << c.true_free + c.false_free << " cells) |";
    }
    md << " " << paper << " |\n";
  };
  row("static (stairs)", t.stairs, "0.91 / 0.93 / 0.93");
  row("quasi-static (doors)", t.doors, "0.98 / 0.99 / 0.99");
  row("dynamic (people)", t.people, "0.95 / 0.94 / 0.93");
  row("overall", t.overall, "0.95 / 0.95 / 0.95");
  md << "\n## Surface gained with closed doors\n\n"
     << "Predicted free area behind the detected closed doors (cells the local map did not know) "
        "over the observed free area.\n\n| p_th | predicted m2 | observed m2 | gain (total) | "
        "gain (mean per scene) | people m2 |\n|---|---|---|---|---|---|\n";
  for (size_t k = 0; k < n; ++k) {
    const double predicted = t.door_cells[k] * t.cell_area;
    const double observed = t.observed_free * t.cell_area;
    md << "| " << Fixed(options.p_th[k], 2) << " | " << Fixed(predicted, 1) << " | "
       << Fixed(observed, 1) << " | +"
       << Fixed(observed > 0 ? 100.0 * predicted / observed : 0.0, 1) << " % | +"
       << Fixed(100.0 * t.gain_sum[k] / std::max<size_t>(1, results.size()), 1) << " % | "
       << Fixed(t.people_cells[k] * t.cell_area, 1) << " |\n";
  }
  md << "\nPaper: up to +10 % at p_th 0.7 and +20 % at 0.5 with closed doors.\n";
  return md.str();
}

std::string ResultsCsv(const BenchExtrapolationOptions& options,
                       const std::vector<ExtrapolationSceneResult>& results) {
  std::ostringstream csv;
  csv << "seed,p_th,closed_doors,doors_detected,hinges_correct,door_fp,stairs_views,"
         "stairs_detected,stairs_fp,tracks,sides_correct,observed_free_cells,"
         "static_tp,static_fp,static_unobserved,doors_tp,doors_fp,doors_unobserved,people_tp,"
         "people_fp,people_unobserved,door_new_cells,people_new_cells\n";
  for (const ExtrapolationSceneResult& r : results) {
    for (size_t k = 0; k < options.p_th.size(); ++k) {
      const ThresholdScores& s = r.scores[k];
      csv << r.seed << "," << options.p_th[k] << "," << r.closed_doors_viewed << ","
          << r.doors_detected << "," << r.hinges_correct << "," << r.door_false_positives << ","
          << r.stairs_views << "," << r.stairs_detected << "," << r.stairs_false_positives << ","
          << r.tracks << "," << r.dominant_sides_correct << "," << r.observed_free_cells;
      for (const PredictionCheck* c : {&s.stairs, &s.doors, &s.people}) {
        csv << "," << c->true_free << "," << c->false_free << "," << c->unobserved;
      }
      csv << "," << s.door_new_cells << "," << s.people_new_cells << "\n";
    }
  }
  return csv.str();
}

nlohmann::json SummaryJson(const BenchExtrapolationOptions& options,
                           const std::vector<ExtrapolationSceneResult>& results, double seconds) {
  const size_t n = options.p_th.size();
  const Totals t = Sum(results, n);
  auto check = [](const PredictionCheck& c) {
    return nlohmann::json{{"true_free", c.true_free},
                          {"false_free", c.false_free},
                          {"unobserved", c.unobserved},
                          {"precision", c.true_free + c.false_free > 0 ? nlohmann::json(c.precision)
                                                                       : nlohmann::json(nullptr)}};
  };
  nlohmann::json thresholds = nlohmann::json::array();
  for (size_t k = 0; k < n; ++k) {
    const double observed = static_cast<double>(t.observed_free);
    thresholds.push_back(
        {{"p_th", options.p_th[k]},
         {"static", check(t.stairs[k])},
         {"quasi_static", check(t.doors[k])},
         {"dynamic", check(t.people[k])},
         {"overall", check(t.overall[k])},
         {"door_predicted_m2", t.door_cells[k] * t.cell_area},
         {"people_predicted_m2", t.people_cells[k] * t.cell_area},
         {"surface_gain", observed > 0 ? t.door_cells[k] / observed : 0.0},
         {"surface_gain_mean_per_scene", t.gain_sum[k] / std::max<size_t>(1, results.size())}});
  }
  return {
      {"scenes", results.size()},
      {"first_seed", options.seed},
      {"seconds", seconds},
      {"machine", MachineDescription()},
      {"recall",
       {{"stairs", t.stairs_views ? static_cast<double>(t.stairs_detected) / t.stairs_views : 0.0},
        {"stairs_views", t.stairs_views},
        {"stairs_false_positives", t.stairs_fp},
        {"doors", t.closed_doors ? static_cast<double>(t.doors_detected) / t.closed_doors : 0.0},
        {"closed_doors", t.closed_doors},
        {"door_false_positives", t.door_fp},
        {"hinges_correct", t.hinges},
        {"dominant_sides_correct", t.sides},
        {"tracks", t.tracks}}},
      {"observed_free_m2", t.observed_free * t.cell_area},
      {"thresholds", thresholds}};
}

// A door counts as recalled when its prediction covers at least this much of its room (m2).
constexpr double kDoorRecallArea = 0.5;

// The floor-plan totals at one threshold; `hinge` 0: jamb a as the hinge, 1: jamb b, 2: both.
struct PlanTotals {
  int64_t true_free = 0, false_free = 0, on_observed = 0, near_room = 0, near_true = 0;
  int64_t unscored = 0;  // on cells without ground truth (a real map's unknown cells)
  int64_t outside_building = 0, unknown_outside = 0;  // of false_free
  int runs = 0, recalled = 0, scored = 0, below_08 = 0, below_07 = 0;
  double median = 0.0, worst = 1.0;
};

PlanTotals SumPlans(const std::vector<PlanDoorResult>& results, size_t k, int hinge) {
  PlanTotals t;
  std::vector<double> per_door;
  for (const PlanDoorResult& r : results) {
    if (hinge != 2 && r.swapped != (hinge == 1)) continue;
    const PlanDoorScore& s = r.scores[k];
    t.true_free += s.true_free, t.false_free += s.false_free, t.on_observed += s.on_observed;
    t.unscored += s.unscored;
    t.outside_building += s.outside_building, t.unknown_outside += s.unknown_outside;
    t.near_room += s.near_room, t.near_true += s.near_true;
    ++t.runs;
    t.recalled += s.true_free * r.cell_area >= kDoorRecallArea;
    if (s.true_free + s.false_free > 0) {
      const double p = static_cast<double>(s.true_free) / (s.true_free + s.false_free);
      per_door.push_back(p);
      t.below_08 += p < 0.8, t.below_07 += p < 0.7;
      t.worst = std::min(t.worst, p);
    }
  }
  t.scored = static_cast<int>(per_door.size());
  if (!per_door.empty()) {
    std::sort(per_door.begin(), per_door.end());
    const size_t m = per_door.size() / 2;
    t.median = per_door.size() % 2 ? per_door[m] : 0.5 * (per_door[m - 1] + per_door[m]);
  }
  return t;
}

std::string PlanReport(const BenchExtrapolationOptions& options,
                       const std::vector<PlanDoorResult>& results, double seconds) {
  std::ostringstream md;
  int end_rooms = 0, second = 0;
  for (const PlanDoorResult& r : results) {
    if (r.swapped) continue;
    end_rooms += r.end_room, second += r.second_doorway;
  }
  md << "# Closed doors on floor plans\n\n"
     << "Command: `fleetmap bench extrapolation --plans " << options.plans << " --unexplored "
     << options.unexplored << " --seed " << options.seed
     << (options.building_outline ? "" : " --no-building-outline")
     << "`  \nMachine: " << MachineDescription() << ", Release build.  \n"
     << "Wall time: " << Fixed(seconds, 1) << " s for " << options.plans << " plans, "
     << results.size() / 2 << " hidden rooms (" << end_rooms << " at an end of the building, "
     << second << " with a second doorway), each door scored with either jamb as the hinge.\n\n"
     << "Precision: predicted cells in the hidden room over all predicted cells. Recall: the "
        "room's cells within 2.5 m of the door's centre that are predicted. A door is recalled "
        "when its prediction covers >= "
     << Fixed(kDoorRecallArea, 1) << " m2 of its room.\n\n"
     << "| p_th | precision (both) | hinge = jamb a | hinge = jamb b | recall <= 2.5 m | door "
        "recall | per-door median | doors < 0.8 | doors < 0.7 | worst door | cells on observed "
        "free | wrong cells outside the building "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto ratio = [](int64_t a, int64_t b) { return Ratio(a, b); };
  for (size_t k = 0; k < options.p_th.size(); ++k) {
    const PlanTotals both = SumPlans(results, k, 2);
    const PlanTotals a = SumPlans(results, k, 0);
    const PlanTotals b = SumPlans(results, k, 1);
    md << "| " << Fixed(options.p_th[k], 2) << " | "
       << ratio(both.true_free, both.true_free + both.false_free) << " ("
       << both.true_free + both.false_free << " cells) | "
       << ratio(a.true_free, a.true_free + a.false_free) << " | "
       << ratio(b.true_free, b.true_free + b.false_free) << " | "
       << ratio(both.near_true, both.near_room) << " | " << ratio(both.recalled, both.runs) << " | "
       << Fixed(both.median, 3) << " | " << both.below_08 << " / " << both.scored << " | "
       << both.below_07 << " / " << both.scored << " | " << Fixed(both.worst, 3) << " | "
       << both.on_observed << " | " << both.outside_building << " |\n";
  }
  return md.str();
}

std::string PlansCsv(const BenchExtrapolationOptions& options,
                     const std::vector<PlanDoorResult>& results) {
  std::ostringstream csv;
  csv << "plan_seed,room,hinge,p_th,door_width,leaf_on_corridor_face,end_room,second_doorway,"
         "true_free,false_free,outside_building,on_observed,near_room,near_true\n";
  for (const PlanDoorResult& r : results) {
    for (size_t k = 0; k < options.p_th.size(); ++k) {
      const PlanDoorScore& s = r.scores[k];
      csv << r.plan_seed << "," << r.room << "," << (r.swapped ? "b" : "a") << ","
          << options.p_th[k] << "," << Fixed(r.width, 3) << "," << r.leaf_on_corridor_face << ","
          << r.end_room << "," << r.second_doorway << "," << s.true_free << "," << s.false_free
          << "," << s.outside_building << "," << s.on_observed << "," << s.near_room << ","
          << s.near_true << "\n";
    }
  }
  return csv.str();
}

nlohmann::json PlansJson(const BenchExtrapolationOptions& options,
                         const std::vector<PlanDoorResult>& results, double seconds) {
  nlohmann::json thresholds = nlohmann::json::array();
  auto frac = [](int64_t a, int64_t b) {
    return b > 0 ? nlohmann::json(static_cast<double>(a) / b) : nlohmann::json(nullptr);
  };
  for (size_t k = 0; k < options.p_th.size(); ++k) {
    nlohmann::json row = {{"p_th", options.p_th[k]}};
    for (const auto& [name, hinge] :
         {std::pair{"both", 2}, std::pair{"hinge_a", 0}, std::pair{"hinge_b", 1}}) {
      const PlanTotals t = SumPlans(results, k, hinge);
      row[name] = {{"precision", frac(t.true_free, t.true_free + t.false_free)},
                   {"true_free", t.true_free},
                   {"false_free", t.false_free},
                   {"outside_building", t.outside_building},
                   {"on_observed", t.on_observed},
                   {"recall_within_radius", frac(t.near_true, t.near_room)},
                   {"door_recall", frac(t.recalled, t.runs)},
                   {"doors", t.runs},
                   {"doors_scored", t.scored},
                   {"doors_below_0_8", t.below_08},
                   {"doors_below_0_7", t.below_07},
                   {"per_door_median", t.median},
                   {"worst_door", t.worst}};
    }
    thresholds.push_back(row);
  }
  return {{"plans", options.plans},
          {"first_seed", options.seed},
          {"hidden_rooms", results.size() / 2},
          {"seconds", seconds},
          {"machine", MachineDescription()},
          {"door_recall_area_m2", kDoorRecallArea},
          {"thresholds", thresholds}};
}

// The hidden rooms of the real maps: one entry per door and hinge choice, with its map's name.
struct RealMapResults {
  std::vector<PlanDoorResult> doors;
  std::vector<std::string> map_of_door;
  struct PerMap {
    std::string name;
    int rooms = 0;  // segmented
    int kept = 0;   // plausible rooms behind one doorway, each a scene
  };
  std::vector<PerMap> maps;
};

// `progress` (may be null) shows the room being scored.
StatusOr<RealMapResults> RunRealMaps(const BenchExtrapolationOptions& options,
                                     ProgressLine* progress) {
  std::vector<std::filesystem::path> yamls;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(options.real_maps_dir, ec)) {
    if (entry.path().extension() == ".yaml") yamls.push_back(entry.path());
  }
  if (ec || yamls.empty()) {
    return InvalidArgumentError(options.real_maps_dir + ": no map YAML files there");
  }
  std::sort(yamls.begin(), yamls.end());
  const RoomSegmentationOptions segmentation_options;
  RealMapResults out;
  for (size_t m = 0; m < yamls.size(); ++m) {
    FLEETMAP_ASSIGN_OR_RETURN(const grid::LoadedMap map, grid::LoadMap(yamls[m].string()));
    const RoomSegmentation segmentation = SegmentRooms(map.grid, segmentation_options);
    const std::vector<uint8_t> building =
        SegmentBuilding(map.grid, segmentation_options.building_closing);
    RealMapResults::PerMap per_map;
    per_map.name = yamls[m].stem().string();
    per_map.rooms = static_cast<int>(segmentation.room_area.size());
    per_map.kept = static_cast<int>(segmentation.doorways.size());
    for (size_t d = 0; d < segmentation.doorways.size(); ++d) {
      if (progress != nullptr) {
        progress->Update(fmt::format("fleetmap bench extrapolation: {} room {}/{}", per_map.name,
                                     d + 1, segmentation.doorways.size()));
      }
      const SegmentedDoorway& doorway = segmentation.doorways[d];
      FloorPlanExperimentOptions experiment;
      experiment.seed = static_cast<uint32_t>(m);
      experiment.p_th = options.p_th;
      experiment.resolution = map.grid.resolution();
      // A real map has its own laser dropouts: none are added.
      experiment.dropout = 0.0;
      experiment.extrapolation.door_building_outline = options.building_outline;
      experiment.extrapolation.door_split_between_doors = options.building_outline;
      if (!options.out_dir.empty()) {
        experiment.example_dir =
            fmt::format("{}/real_maps/{}_room_{}", options.out_dir, per_map.name, doorway.room);
      }
      const FloorPlan plan =
          PlanForRoom(map.grid, segmentation, doorway, segmentation_options, building);
      FLEETMAP_ASSIGN_OR_RETURN(std::vector<PlanDoorResult> results,
                                RunHiddenRoomExperiment(plan, experiment));
      for (PlanDoorResult& r : results) {
        r.room = doorway.room;
        out.doors.push_back(std::move(r));
        out.map_of_door.push_back(per_map.name);
      }
    }
    out.maps.push_back(per_map);
  }
  if (progress != nullptr) progress->Finish();
  return out;
}

// Precision of one door run at threshold k, if it predicted anything.
std::optional<double> DoorPrecision(const PlanDoorResult& r, size_t k) {
  const PlanDoorScore& s = r.scores[k];
  if (s.true_free + s.false_free == 0) return std::nullopt;
  return static_cast<double>(s.true_free) / (s.true_free + s.false_free);
}

std::string RealMapsReport(const BenchExtrapolationOptions& options, const RealMapResults& real,
                           double seconds) {
  std::ostringstream md;
  int kept = 0;
  for (const RealMapResults::PerMap& m : real.maps) kept += m.kept;
  md << "# Closed doors on real maps\n\n"
     << "Command: `fleetmap bench extrapolation --real-maps " << options.real_maps_dir
     << " --scenes 0" << (options.building_outline ? "" : " --no-building-outline")
     << "`  \nMachine: " << MachineDescription() << ", Release build.  \n"
     << "Wall time: " << Fixed(seconds, 1) << " s for " << real.maps.size() << " maps, " << kept
     << " hidden rooms (segmented automatically: rooms of 4-80 m2 behind exactly one doorway "
        "0.6-1.3 m wide), each door scored with either jamb as the hinge.\n\n"
     << "Strict precision (the headline, and every per-door figure): a predicted cell on a cell "
        "the source map left unknown is wrong when it lies outside the building (the known "
        "cells closed by a 1 m disc, holes filled) and unscored inside it: nobody scanned it, so "
        "it may be the room's or not. Lenient precision (until issue 36): unscored either way. "
        "The last columns count the unscored cells inside the building and give the precision "
        "if they were all wrong too.\n\n"
     << "| p_th | precision, strict (both) | lenient | hinge = jamb a | hinge = jamb b | recall "
        "<= 2.5 m | door recall | per-door median | doors < 0.8 | doors < 0.7 | worst door | "
        "cells on observed free | wrong cells outside the building | unscored cells | "
        "precision, unscored counted wrong |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (size_t k = 0; k < options.p_th.size(); ++k) {
    const PlanTotals both = SumPlans(real.doors, k, 2);
    const PlanTotals a = SumPlans(real.doors, k, 0);
    const PlanTotals b = SumPlans(real.doors, k, 1);
    std::string worst_name = "-";
    double worst = 2.0;
    for (size_t i = 0; i < real.doors.size(); ++i) {
      const std::optional<double> p = DoorPrecision(real.doors[i], k);
      if (p && *p < worst) {
        worst = *p;
        worst_name = fmt::format("{} room {} hinge {}", real.map_of_door[i], real.doors[i].room,
                                 real.doors[i].swapped ? "b" : "a");
      }
    }
    md << "| " << Fixed(options.p_th[k], 2) << " | "
       << Ratio(both.true_free, both.true_free + both.false_free) << " ("
       << both.true_free + both.false_free << " cells) | "
       << Ratio(both.true_free, both.true_free + both.false_free - both.unknown_outside) << " | "
       << Ratio(a.true_free, a.true_free + a.false_free) << " | "
       << Ratio(b.true_free, b.true_free + b.false_free) << " | "
       << Ratio(both.near_true, both.near_room) << " | " << Ratio(both.recalled, both.runs) << " | "
       << Fixed(both.median, 3) << " | " << both.below_08 << " / " << both.scored << " | "
       << both.below_07 << " / " << both.scored << " | "
       << (worst <= 1.0 ? Fixed(worst, 3) + " (" + worst_name + ")" : std::string("n/a")) << " | "
       << both.on_observed << " | " << both.outside_building << " | " << both.unscored << " | "
       << Ratio(both.true_free, both.true_free + both.false_free + both.unscored) << " |\n";
  }
  md << "\n| map | rooms segmented | hidden rooms | door runs |";
  for (double p : options.p_th) md << " strict precision / doors < 0.7 at " << Fixed(p, 2) << " |";
  md << "\n|---|---|---|---|";
  for (size_t k = 0; k < options.p_th.size(); ++k) md << "---|";
  md << "\n";
  for (const RealMapResults::PerMap& m : real.maps) {
    std::vector<PlanDoorResult> mine;
    for (size_t i = 0; i < real.doors.size(); ++i) {
      if (real.map_of_door[i] == m.name) mine.push_back(real.doors[i]);
    }
    md << "| " << m.name << " | " << m.rooms << " | " << m.kept << " | " << mine.size() << " |";
    for (size_t k = 0; k < options.p_th.size(); ++k) {
      const PlanTotals t = SumPlans(mine, k, 2);
      md << " " << Ratio(t.true_free, t.true_free + t.false_free) << " / " << t.below_07 << " |";
    }
    md << "\n";
  }
  return md.str();
}

std::string RealMapsCsv(const BenchExtrapolationOptions& options, const RealMapResults& real) {
  std::ostringstream csv;
  csv << "map,room,hinge,p_th,door_width,true_free,false_free,unknown_outside,unscored,"
         "on_observed,near_room,near_true\n";
  for (size_t i = 0; i < real.doors.size(); ++i) {
    const PlanDoorResult& r = real.doors[i];
    for (size_t k = 0; k < options.p_th.size(); ++k) {
      const PlanDoorScore& s = r.scores[k];
      csv << real.map_of_door[i] << "," << r.room << "," << (r.swapped ? "b" : "a") << ","
          << options.p_th[k] << "," << Fixed(r.width, 3) << "," << s.true_free << ","
          << s.false_free << "," << s.unknown_outside << "," << s.unscored << "," << s.on_observed
          << "," << s.near_room << "," << s.near_true << "\n";
    }
  }
  return csv.str();
}

nlohmann::json RealMapsJson(const BenchExtrapolationOptions& options, const RealMapResults& real,
                            double seconds) {
  auto frac = [](int64_t a, int64_t b) {
    return b > 0 ? nlohmann::json(static_cast<double>(a) / b) : nlohmann::json(nullptr);
  };
  nlohmann::json thresholds = nlohmann::json::array();
  for (size_t k = 0; k < options.p_th.size(); ++k) {
    const PlanTotals t = SumPlans(real.doors, k, 2);
    thresholds.push_back(
        {{"p_th", options.p_th[k]},
         {"precision", frac(t.true_free, t.true_free + t.false_free)},
         {"precision_lenient", frac(t.true_free, t.true_free + t.false_free - t.unknown_outside)},
         {"unknown_outside", t.unknown_outside},
         {"precision_unscored_counted_wrong",
          frac(t.true_free, t.true_free + t.false_free + t.unscored)},
         {"true_free", t.true_free},
         {"false_free", t.false_free},
         {"unscored", t.unscored},
         {"on_observed", t.on_observed},
         {"recall_within_radius", frac(t.near_true, t.near_room)},
         {"door_recall", frac(t.recalled, t.runs)},
         {"doors", t.runs},
         {"doors_scored", t.scored},
         {"doors_below_0_8", t.below_08},
         {"doors_below_0_7", t.below_07},
         {"per_door_median", t.median},
         {"worst_door", t.worst}});
  }
  nlohmann::json maps = nlohmann::json::array();
  for (const RealMapResults::PerMap& m : real.maps) {
    maps.push_back({{"map", m.name}, {"rooms_segmented", m.rooms}, {"hidden_rooms", m.kept}});
  }
  return {{"real_maps_dir", options.real_maps_dir},
          {"maps", maps},
          {"seconds", seconds},
          {"machine", MachineDescription()},
          {"door_recall_area_m2", kDoorRecallArea},
          {"thresholds", thresholds}};
}

}  // namespace

int RunBenchExtrapolation(const BenchExtrapolationOptions& options, std::ostream& out,
                          std::ostream& err) {
  const std::string prefix = "fleetmap bench extrapolation: ";
  if (options.scenes < 0 || options.scenes > 10000 || options.plans < 0 || options.plans > 10000 ||
      (options.scenes + options.plans == 0 && options.real_maps_dir.empty())) {
    err << prefix << "--scenes " << options.scenes << ", --plans " << options.plans
        << ": each must be in [0, 10000], and not both 0 without --real-maps\n";
    return cli::kExitBadInput;
  }
  if (!(options.unexplored >= 0.0 && options.unexplored <= 1.0)) {
    err << prefix << "--unexplored: " << options.unexplored << " is not in [0, 1]\n";
    return cli::kExitBadInput;
  }
  if (options.p_th.empty() || static_cast<int>(options.p_th.size()) > kMaxThresholds) {
    err << prefix << "--pth: give 1 to " << kMaxThresholds << " thresholds\n";
    return cli::kExitBadInput;
  }
  for (double p : options.p_th) {
    if (!(p > 0.0 && p < 1.0)) {
      err << prefix << "--pth: " << p << " is not in (0, 1)\n";
      return cli::kExitBadInput;
    }
  }
  if (!options.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.out_dir, ec);
    if (ec) {
      err << prefix << "--out: " << options.out_dir << ": cannot create the directory\n";
      return cli::kExitBadInput;
    }
  }
  // Each experiment's report, CSV and JSON under --out (none without it); false after an error,
  // which it prints.
  const auto write_outputs = [&](const std::vector<std::pair<std::string, std::string>>& files) {
    if (options.out_dir.empty()) return true;
    for (const auto& [name, contents] : files) {
      const Status written = WriteFileAtomically(options.out_dir + "/" + name, contents);
      if (!written.ok()) {
        err << prefix << written.message() << "\n";
        return false;
      }
    }
    return true;
  };
  // Progress on `err`, one line per experiment (none with --no-progress).
  std::optional<ProgressLine> progress_line;
  if (options.progress) {
    progress_line.emplace(err, ProgressLineOptions{.terminal = options.err_is_terminal});
  }
  ProgressLine* progress = progress_line ? &*progress_line : nullptr;
  const auto show = [&](const std::string& text) {
    if (progress != nullptr) progress->Update(text);
  };
  const auto end_line = [&] {
    if (progress != nullptr) progress->Finish();
  };
  if (!options.real_maps_dir.empty()) {
    const auto real_start = std::chrono::steady_clock::now();
    StatusOr<RealMapResults> real = RunRealMaps(options, progress);
    if (!real.ok()) {
      end_line();
      err << prefix << "--real-maps: " << real.status().message() << "\n";
      return cli::kExitBadInput;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - real_start).count();
    const std::string report = RealMapsReport(options, real.value(), seconds);
    out << report << (options.scenes + options.plans > 0 ? "\n" : "");
    if (!write_outputs(
            {{"real_maps.md", report},
             {"real_maps.csv", RealMapsCsv(options, real.value())},
             {"real_maps.json", RealMapsJson(options, real.value(), seconds).dump(2) + "\n"}})) {
      return cli::kExitBadInput;
    }
  }
  if (options.plans > 0) {
    const auto plans_start = std::chrono::steady_clock::now();
    std::vector<PlanDoorResult> plan_results;
    for (int i = 0; i < options.plans; ++i) {
      FloorPlanExperimentOptions plan;
      plan.seed = options.seed + static_cast<uint32_t>(i);
      plan.p_th = options.p_th;
      plan.unexplored_room_probability = options.unexplored;
      plan.extrapolation.door_building_outline = options.building_outline;
      plan.extrapolation.door_split_between_doors = options.building_outline;
      if (i == 0 && !options.out_dir.empty()) {
        plan.example_dir = options.out_dir + "/plan_" + std::to_string(plan.seed);
      }
      show(fmt::format("{}plan {}/{}", prefix, i + 1, options.plans));
      StatusOr<std::vector<PlanDoorResult>> result = RunFloorPlanExperiment(plan);
      if (!result.ok()) {
        end_line();
        err << prefix << "plan " << plan.seed << ": " << result.status().message() << "\n";
        return cli::kExitBadInput;
      }
      for (PlanDoorResult& r : result.value()) plan_results.push_back(std::move(r));
    }
    end_line();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - plans_start).count();
    const std::string report = PlanReport(options, plan_results, seconds);
    out << report << (options.scenes > 0 ? "\n" : "");
    if (!write_outputs(
            {{"plans.md", report},
             {"plans.csv", PlansCsv(options, plan_results)},
             {"plans.json", PlansJson(options, plan_results, seconds).dump(2) + "\n"}})) {
      return cli::kExitBadInput;
    }
  }
  if (options.scenes == 0) return cli::kExitOk;
  const auto start = std::chrono::steady_clock::now();
  std::vector<ExtrapolationSceneResult> results;
  for (int i = 0; i < options.scenes; ++i) {
    ExtrapolationSceneOptions scene;
    scene.seed = options.seed + static_cast<uint32_t>(i);
    scene.p_th = options.p_th;
    if (i == 0 && !options.out_dir.empty()) {
      scene.example_dir = options.out_dir + "/scene_" + std::to_string(scene.seed);
    }
    show(fmt::format("{}scene {}/{}", prefix, i + 1, options.scenes));
    StatusOr<ExtrapolationSceneResult> result = RunExtrapolationScene(scene);
    if (!result.ok()) {
      end_line();
      err << prefix << "seed " << scene.seed << ": " << result.status().message() << "\n";
      return cli::kExitBadInput;
    }
    results.push_back(std::move(result).value());
  }
  end_line();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string report = Report(options, results, seconds);
  out << report;
  if (!write_outputs({{"report.md", report},
                      {"results.csv", ResultsCsv(options, results)},
                      {"results.json", SummaryJson(options, results, seconds).dump(2) + "\n"}})) {
    return cli::kExitBadInput;
  }
  return cli::kExitOk;
}

void AddBenchExtrapolationCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<BenchExtrapolationOptions>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "extrapolation",
      "Map extrapolation on simulated indoor scenes and floor plans (recall, precision, surface)");
  command->add_option("--out", options->out_dir, "output directory (report, CSV, JSON)");
  command->add_option("--scenes", options->scenes, "number of scenes")->capture_default_str();
  command->add_option("--plans", options->plans, "number of floor plans (closed doors)")
      ->capture_default_str();
  command->add_option("--real-maps", options->real_maps_dir,
                      "directory of real maps (*.yaml): rooms behind closed doors");
  command
      ->add_option("--unexplored", options->unexplored,
                   "floor plans: probability that the robot never went into a room")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "first scene and plan seed")->capture_default_str();
  command->add_option("--pth", options->p_th, "thresholds in (0, 1), comma separated")
      ->delimiter(',')
      ->capture_default_str();
  command->add_flag("!--no-building-outline", options->building_outline,
                    "door predictions without the building's outline and the other doors in "
                    "their wall (issue 21's algorithm)");
  command->add_flag("!--no-progress", options->progress, "no progress on stderr");
  command->callback([options, exit_code] {
    options->err_is_terminal = ProgressLine::StderrIsTerminal();
    *exit_code = RunBenchExtrapolation(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::bench
