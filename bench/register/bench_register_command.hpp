#pragma once

// `fleetmap bench register --maps DIR [--pairs-per-overlap N] [--seed S] [--csv F] [--json F]`:
// issue 18's registration benchmark. Cuts pairs of robot maps from every map_server map in DIR
// at 20 / 35 / 50 / 70 % overlap (bench/register/map_pair_generator.hpp), registers each with
// fleetmap and with m-explore's pipeline in the same run (one core), and prints per overlap and
// in total: success %, false accepts %, median and worst time per pair; then the reliability of
// fleetmap's confidence. `--synthetic K` uses K terrains of common/sim instead of DIR and
// prints the isotonic fit of the confidence calibration (how its default knots were made).
// Progress goes to stderr.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

namespace fleetmap::bench {

struct BenchRegisterOptions {
  std::string maps_dir;
  int synthetic_maps = 0;  // > 0: office terrains instead of maps_dir, and fit the calibration
  int pairs_per_overlap = 4;
  uint32_t seed = 1;
  std::string csv_path;   // empty: none
  std::string json_path;  // empty: none
  bool skip_mexplore = false;
};

// Bad options or unreadable maps print a message naming them and return cli::kExitBadInput.
int RunBenchRegister(const BenchRegisterOptions& options, std::ostream& out, std::ostream& err);

void AddBenchRegisterCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
