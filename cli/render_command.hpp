#pragma once

// `fleetmap render IN.(vmap|yaml) -o OUT.(svg|png) [--like MAP.yaml]`: a picture of a vector map
// or of a grid. A .vmap renders to SVG (vector_map::ToSvg) or PNG (drawn over --like's geometry,
// or the tiles' bounding box); a grid renders to PNG (trinary shades) or to an SVG that embeds
// that PNG, scaled to metres like the vector SVGs.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <ostream>
#include <string>

#include "cli/inputs/command_inputs.hpp"

namespace fleetmap::cli {

struct RenderCommandOptions {
  std::string input;
  std::string output;
  std::string like_yaml;
  int64_t max_cells = kDefaultMaxCells;
};

int RunRender(const RenderCommandOptions& options, std::ostream& out, std::ostream& err);

void AddRenderCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
