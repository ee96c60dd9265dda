#pragma once

// `fleetmap terrain --kind office --size 40 --seed 7 -o gt.yaml [--resolution R] [--geojson F
// [--georef LAT LON YAW]]`: generates a simulated terrain (docs/simulator.md) and writes its
// ground-truth grid as a map_server map (YAML + PGM) and, optionally, its exact geometry as
// GeoJSON (map-frame metres, or WGS84 with --georef).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "common/gis/georeference.hpp"

namespace fleetmap::cli {

struct TerrainCommandOptions {
  std::string kind = "office";
  double size = 10.0;
  uint32_t seed = 0;
  double resolution = 0.05;
  std::string output_yaml;
  std::string geojson;
  std::optional<gis::GeoOrigin> georef;  // the map frame on Earth: GeoJSON in WGS84
};

// On bad input (unknown kind, size or resolution out of bounds, unwritable file) prints a message
// naming the option or file to `err` and returns kExitBadInput; kExitOk otherwise.
int RunTerrain(const TerrainCommandOptions& options, std::ostream& out, std::ostream& err);

void AddTerrainCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
