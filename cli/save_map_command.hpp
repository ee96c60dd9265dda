#pragma once

// `fleetmap save-map -o fused.yaml`: the map saver. Joins the fleet as a reader (like nav2's
// map_saver_cli subscribes to /map), waits for the fused map on rt/fleetmap/map, and writes it as
// a map_server YAML + image with map_saver's conventions; optionally the fused vector tiles of
// rt/fleetmap/fused_tiles as GeoJSON and .vmap. With `--georef LAT LON YAW` (where the fleet frame
// lies on Earth) the GeoJSON is WGS84 longitude / latitude and NAME.georef.yaml beside the map
// YAML records the georeference (the map YAML itself is unchanged).

#include <CLI/CLI.hpp>
#include <optional>
#include <ostream>
#include <string>

#include "cli/fleet_reader_options.hpp"
#include "common/gis/georeference.hpp"

namespace fleetmap::cli {

struct SaveMapOptions {
  std::string yaml_path;
  std::string image_format = "pgm";  // pgm or png
  double occupied_thresh = 0.65;     // map_saver's --occ
  double free_thresh = 0.196;        // map_saver's --free (0.196: the 205 shade reads back unknown)
  std::string geojson_path;          // the fused vector map, merged (empty: none)
  std::string vmap_path;             // the fused vector tiles (empty: none)
  std::optional<gis::GeoOrigin> georef;  // the fleet frame on Earth (none: GeoJSON in metres)
  double timeout_s = 30.0;               // for the first fused map
  double settle_s = 2.0;                 // then keep the newest map and tiles this long
  FleetReaderOptions fleet;
  bool err_is_terminal = false;  // progress redrawn in place (else a line every 10 s)
};

// Runs the saver; progress and errors (naming the path or the domain and what is wrong) go to
// `err`, the files written to `out`. kExitOk; kExitBadInput for bad options or an unwritable
// path; 1 when no fused map came within the timeout.
int RunSaveMap(const SaveMapOptions& options, std::ostream& out, std::ostream& err);

void AddSaveMapCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
