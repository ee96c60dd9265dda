#pragma once

// `fleetmap vectorize MAP.yaml -o OUT.vmap [--epsilon E] [--free-epsilon F]
// [--method default|paper] [--tile-size T] [--geojson F [--georef LAT LON YAW]] [--svg F]
// [--png F] [--json]`: vectorizes a grid tile by tile (fleet frame = map frame) and writes the
// .vmap, optionally GeoJSON (frame metres, or WGS84 with --georef) / SVG / PNG pictures of it.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "cli/inputs/command_inputs.hpp"
#include "common/gis/georeference.hpp"

namespace fleetmap::cli {

struct VectorizeCommandOptions {
  std::string map_yaml;
  std::string output_vmap;
  double epsilon = 0.0;  // metres; 0 (not given) picks sqrt(2) * resolution
  bool epsilon_given = false;
  // Metres; the tolerance of the free-space outlines, 0 (not given) = epsilon. Smaller keeps the
  // free / unknown border and one-cell unknown specks more faithfully, at more bytes.
  double free_epsilon = 0.0;
  bool free_epsilon_given = false;
  std::string method = "default";
  double tile_size = 10.0;  // metres
  std::string geojson_path;
  std::optional<gis::GeoOrigin> georef;  // the map frame on Earth: GeoJSON in WGS84
  std::string svg_path;
  std::string png_path;
  bool json = false;
  int64_t max_cells = kDefaultMaxCells;
};

// Prints a short summary (or one JSON line) to `out`. Bad input: "<file>: <problem>" on `err`
// and kExitBadInput.
int RunVectorize(const VectorizeCommandOptions& options, std::ostream& out, std::ostream& err);

void AddVectorizeCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
