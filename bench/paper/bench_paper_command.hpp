#pragma once

// `fleetmap bench paper --out DIR [--seed S] [--sizes 10,40,80]`: the Vector Maps paper's
// experiment (ALGORITHMS.md 1.2) on simulated terrains: maze, office and unstructured at each size,
// explored and mapped by a simulated robot. Writes DIR/report.md, DIR/results.csv, bar charts
// (DIR/sizes.png, DIR/quality_<kind>_<size>.png) and each map as PNG under DIR/maps/. A progress
// bar runs on stderr.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace fleetmap::bench {

struct BenchPaperOptions {
  std::string out_dir;
  uint32_t seed = 1;
  std::vector<double> sizes = {10.0, 40.0, 80.0};
  std::vector<std::string> kinds = {"maze", "office", "unstructured"};
  double resolution = 0.05;
  double laser_fov_deg = 180.0;
  double laser_step_deg = 1.0;
  double laser_range = 30.0;
  bool slam_error = true;
  bool line_refit = true;  // VectorizerOptions::refit_lines (off only to measure it)
  bool progress = true;
  bool err_is_terminal = false;  // the bar redrawn in place (else a line every 10 s)
};

// Bad options (unknown kind, size out of bounds, resolution <= 0, a laser with no rays) print a
// message naming the option and return cli::kExitBadInput, before anything runs.
int RunBenchPaper(const BenchPaperOptions& options, std::ostream& out, std::ostream& err);

void AddBenchPaperCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
