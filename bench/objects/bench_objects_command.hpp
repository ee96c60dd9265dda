#pragma once

// `fleetmap bench objects [--out DIR] [--starts 20] [--seed S]`: the object-learning paper's
// comparison (ALGORITHMS.md 2) on simulated data like its second data set: 4 objects of 3 shapes
// (two chairs, a bin, a box) in a lab, 9 mapping sessions, 2 or 3 objects per session (no map
// shows all 4). Reports, for the hierarchical and the flat model, how many random starts reach
// the good solution, the leave-one-map-out test log-likelihood, the (N, M) model selection
// chooses and the time; prints a table, writes DIR/results.json, DIR/results.csv and the maps
// under DIR/maps/ (so `fleetmap learn-objects DIR/maps/*.yaml` can be run on them).
//
// With `--maps DIR_OR_FILES` (map_server YAML floors), also the real-plan benchmark of issue 22:
// for each floor a series of maps with furniture drawn in free space and moved between them
// (RealPlanSeries), learned on as `learn-objects` would, and scored against the drawn pieces
// (precision / recall by position), with the learned (N, M), time and peak memory; written to
// DIR/real_plans.json, DIR/real_plans.csv and the series' maps to DIR/real_plans/<floor>/.
//
// With `--small-pieces N` (and only that): small objects against SLAM specks on N map pairs
// (small_piece_experiment.hpp): recall of pieces of 4-7 cells, precision, false objects per
// 100 m2 of noise-only pairs; DIR/small_pieces.md.
//
// With `--speck-census --maps MAPS` (and only that): how speckled each map is (speck_census.hpp),
// beside the small-piece benchmark's synthetic noise at 1, 2, 5 and 10 events per 100 m2, so its
// speck densities can be read against real maps; DIR/speck_census.csv.
//
// With `--contrast` (and only that): the paper's flat/hierarchical contrast searched over
// conditions (contrast_experiment.hpp), good starts of each model per condition over
// `--data-sets` simulated data sets; DIR/contrast.md, contrast.csv, contrast.json.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace fleetmap::bench {

struct BenchObjectsOptions {
  std::string out_dir;  // empty: print only
  int starts = 20;
  uint32_t seed = 1;
  std::string terrain = "lab";  // lab or office
  double size = 10.0;           // metres
  int sessions = 9;
  int restarts = 0;  // random starts per (N, M) in model selection and cross validation; 0: default
  // The real-plan benchmark: floors (YAML files, or directories of them); empty: not run.
  std::vector<std::string> floors;
  int plan_maps = 4;              // maps per series
  int plan_pieces = 40;           // pieces per map
  int plan_width = 800;           // cells
  int plan_height = 544;          // cells
  bool skip_sim = false;          // only the real-plan benchmark
  double memory_budget_mb = 0.0;  // the learner's budget (0: its default)
  // Small objects against SLAM specks (small_piece_experiment.hpp): pairs to run; 0: not run.
  // When set, only this benchmark runs.
  int small_pieces = 0;
  double speck_events = 5.0;      // per 100 m2 per map
  double isolation_radius = 0.5;  // SnapshotOptions::isolation_radius_m
  bool small_in_one_map = false;  // SmallPieceOptions::small_in_one_map
  bool speck_census = false;      // the census of --maps (speck_census.hpp); only this runs
  // The flat/hierarchical contrast (contrast_experiment.hpp): every condition on this many data
  // seeds from --seed, --starts starts each. When set, only this benchmark runs.
  bool contrast = false;
  int contrast_data_sets = 3;
  std::vector<std::string> contrast_conditions;  // names; empty: all
};

// Bad options print a message naming the option and return cli::kExitBadInput.
int RunBenchObjects(const BenchObjectsOptions& options, std::ostream& out, std::ostream& err);

void AddBenchObjectsCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
