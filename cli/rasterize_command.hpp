#pragma once

// `fleetmap rasterize IN.vmap -o OUT.yaml [--like MAP.yaml] [--resolution R]`: a .vmap back to a
// three-state grid (occupied near an edge, free inside a free polygon, unknown elsewhere; see
// vector_map::Rasterizer), written as a map_server YAML + PGM. Geometry: by default the bounding
// box of the tile squares at the .vmap's resolution (or R); --like copies a grid's size,
// resolution and origin.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "cli/inputs/command_inputs.hpp"

namespace fleetmap::cli {

struct RasterizeCommandOptions {
  std::string vmap;
  std::string output_yaml;
  std::string like_yaml;
  double resolution = 0.0;
  bool resolution_given = false;
  int64_t max_cells = kDefaultMaxCells;
};

int RunRasterize(const RasterizeCommandOptions& options, std::ostream& out, std::ostream& err);

void AddRasterizeCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
