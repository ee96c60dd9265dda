#pragma once

// `fleetmap bench register --maps DIR [--repeated K] [--no-drift] [--pairs-per-overlap N]
// [--seed S] [--csv F] [--json F]`: issue 18's registration benchmark with issue 31's additions.
// Cuts pairs of robot maps from every map_server map in DIR and from K repeated-structure
// terrains (warehouse, office rows, corridors) at 20 / 35 / 50 / 70 % overlap
// (bench/register/map_pair_generator.hpp), registers each, and again with B drifted (a smooth
// warp), with fleetmap (found: at the server's placement bar) and with m-explore's pipeline in
// the same run (one core), and prints per group of pairs and overlap: success %, false accepts
// %, median and worst time per pair; then the reliability of fleetmap's confidence.
// `--synthetic K` uses K synthetic terrains (common/sim's kinds and the repeated ones) instead
// of DIR and prints the isotonic fit of the confidence calibration (how its default knots were
// made). `--growing N` grows each B in N steps and reports when the placer's sequential test
// would place it (growing_experiment.hpp). Progress goes to stderr.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "common/registration/registration.hpp"

namespace fleetmap::bench {

struct BenchRegisterOptions {
  std::string maps_dir;
  int synthetic_maps = 0;  // > 0: synthetic terrains instead of maps_dir, and fit the calibration
  int repeated_maps = 3;   // with maps_dir: repeated-structure terrains, a group of their own
  bool no_drift = false;   // skip the drifted pairs
  int pairs_per_overlap = 4;
  uint32_t seed = 1;
  std::string csv_path;   // empty: none
  std::string json_path;  // empty: none
  bool skip_mexplore = false;
  // > 1: the sequential test on growing maps (growing_experiment.hpp) instead of the pairs.
  int growing_steps = 0;
  // The registration's drift bound (RegistrationOptions::max_drift_per_m, 0.03 by default); 0
  // verifies rigidly, for a side-by-side figure.
  double max_drift_per_m = registration::RegistrationOptions{}.max_drift_per_m;
  // MapPairOptions::wall_noise: independent noise on each map's walls (0: crops share them).
  double wall_noise = 0.0;
  bool err_is_terminal = false;  // progress redrawn in place (else a line every 10 s)
};

// Bad options or unreadable maps print a message naming them and return cli::kExitBadInput.
int RunBenchRegister(const BenchRegisterOptions& options, std::ostream& out, std::ostream& err);

void AddBenchRegisterCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
