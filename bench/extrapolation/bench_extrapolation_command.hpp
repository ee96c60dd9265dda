#pragma once

// `fleetmap bench extrapolation [--out DIR] [--scenes N] [--plans M] [--unexplored P] [--seed S]
// [--pth 0.5,0.6,0.7]`: the map extrapolation experiment (extrapolation_experiment.hpp) over N
// simulated indoor scenes (seeds S .. S + N - 1), and the closed-door experiment on M floor plans
// (floor_plan_experiment.hpp, plan seeds S .. S + M - 1; with --out also DIR/plans.csv, one row per
// door, hinge choice and threshold, and DIR/plans.json, the totals). Prints the paper's tables
// (detection recall of stairs and doors; free-space precision per class and threshold; the surface
// gained behind closed doors) and, with --out, writes DIR/report.md, DIR/results.csv (one row per
// scene and threshold) and DIR/results.json (the totals), and the first scene's inputs under
// DIR/scene_<S>/ (local map, entities, ground truths, camera points) to try `fleetmap extrapolate`
// on. With --real-maps DIR, the closed-door experiment on the rooms segmented in each map of DIR
// (room_segmentation.hpp), with --out also DIR/real_maps.md, .csv (one row per door, hinge choice
// and threshold) and .json (the totals), and each hidden room's scene (hinge at jamb a) under
// DIR/real_maps/<map>_room_<r>/ for `fleetmap extrapolate`. Bad options exit with code 2 before
// anything runs.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace fleetmap::bench {

struct BenchExtrapolationOptions {
  std::string out_dir;
  int scenes = 20;
  int plans = 0;  // floor plans; --scenes may be 0 when plans > 0
  // Real maps (*.yaml) whose rooms are hidden behind closed doors (room_segmentation.hpp);
  // --scenes and --plans may both be 0 when set.
  std::string real_maps_dir;
  uint32_t seed = 1;
  // Per floor-plan room: the robot never went in (floor_plan.hpp); 0 gives issue 21's plans.
  double unexplored = 0.3;
  // Door predictions bounded by the building's outline and the other closed doors in their wall
  // (ExtrapolationOptions::door_building_outline, door_split_between_doors); off gives the
  // algorithm of issue 21, the "before" of issue 36.
  bool building_outline = true;
  std::vector<double> p_th = {0.5, 0.6, 0.7};
  bool progress = true;
  bool err_is_terminal = false;  // progress redrawn in place (else a line every 10 s)
};

int RunBenchExtrapolation(const BenchExtrapolationOptions& options, std::ostream& out,
                          std::ostream& err);

void AddBenchExtrapolationCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
