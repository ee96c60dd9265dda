#pragma once

// `fleetmap bench objects [--out DIR] [--starts 20] [--seed S]`: the object-learning paper's
// comparison (ALGORITHMS.md 2) on simulated data like its second data set: 4 objects of 3 shapes
// (two chairs, a bin, a box) in a lab, 9 mapping sessions, 2 or 3 objects per session (no map
// shows all 4). Reports, for the hierarchical and the flat model, how many random starts reach
// the good solution, the leave-one-map-out test log-likelihood, the (N, M) model selection
// chooses and the time; prints a table, writes DIR/results.json, DIR/results.csv and the maps
// under DIR/maps/ (so `fleetmap learn-objects DIR/maps/*.yaml` can be run on them).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

namespace fleetmap::bench {

struct BenchObjectsOptions {
  std::string out_dir;  // empty: print only
  int starts = 20;
  uint32_t seed = 1;
  std::string terrain = "lab";  // lab or office
  double size = 10.0;           // metres
  int sessions = 9;
  int restarts = 0;  // random starts per (N, M) in model selection and cross validation; 0: default
};

// Bad options print a message naming the option and return cli::kExitBadInput.
int RunBenchObjects(const BenchObjectsOptions& options, std::ostream& out, std::ostream& err);

void AddBenchObjectsCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
