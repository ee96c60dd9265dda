#pragma once

// `fleetmap extrapolate --map LOCAL.yaml --entities ENTITIES.json [--cloud POINTS.ply]
// [--viewpoint X,Y] --out DIR [--pth 0.5,0.6,0.7] [--georef LAT LON YAW] [--no-building-outline]`:
// map extrapolation on files (docs/extrapolation.md). Reads a local map and the entities a robot
// recognised (doors, stairs, people's tracks), optionally detects more stairs and closed doors in a
// PLY point cloud, and for each threshold writes under DIR/pth_<p>/ the sub-map graph (graph.json),
// every predicted sub-map as a map YAML + PGM, the floor's predicted free space and the
// extrapolated map (YAML + PGM), the predicted free space as GeoJSON polygons (map-frame metres, or
// WGS84 with --georef) and a PNG overlay. DIR/entities.json holds the entities used (file +
// detected).
//
// Bad input (unreadable map, entities file or point cloud; a bad --pth) prints a message naming
// the file or flag and returns kExitBadInput. Unusable entities are skipped with a warning on
// stderr naming each, and the rest is used.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cli/inputs/command_inputs.hpp"
#include "common/gis/georeference.hpp"

namespace fleetmap::cli {

struct ExtrapolateCommandOptions {
  std::string map_yaml;
  std::string entities_json;
  std::string cloud_ply;
  std::vector<double> viewpoint;  // empty, or x, y (map frame) of the sensor that took the cloud
  std::string out_dir;
  std::vector<double> p_th = {0.5};
  std::optional<gis::GeoOrigin> georef;  // the map frame on Earth: predicted_free.geojson in WGS84
  int64_t max_cells = kDefaultMaxCells;
  int64_t max_points = 20'000'000;
  // Door predictions bounded by the building's outline (ExtrapolationOptions::
  // door_building_outline); --no-building-outline shows them without it.
  bool building_outline = true;
};

int RunExtrapolate(const ExtrapolateCommandOptions& options, std::ostream& out, std::ostream& err);

void AddExtrapolateCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
