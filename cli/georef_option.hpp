#pragma once

// `--georef LAT LON YAW`, the option of every `fleetmap` command that writes GeoJSON (save-map,
// vectorize, extrapolate, terrain; docs/file-formats.md, "GeoJSON in WGS84: --georef"): the
// frame's origin is at WGS84 latitude LAT and longitude LON, its x axis YAW degrees
// counter-clockwise from East, and the GeoJSON is written in longitude and latitude (RFC 7946)
// instead of frame metres. Without it the GeoJSON stays in frame metres with nav2_route's
// EPSG:3857 `crs` member.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "common/core/status.hpp"
#include "common/gis/georeference.hpp"

namespace fleetmap::cli {

// Adds `--georef LAT LON YAW` to `command`; `frame` names the frame the origin belongs to in the
// help ("map", "fleet"). A value that is not a number, a latitude outside [-90, 90] or a
// longitude outside [-180, 180] is a usage error naming --georef (exit 2,
// common/config/command_line.hpp).
CLI::Option* AddGeorefOption(CLI::App* command, const std::string& frame,
                             std::optional<gis::GeoOrigin>* origin);

// `collection` (a GeoJSON export in frame metres) as the command writes it: as it is without a
// georeference, in WGS84 longitude and latitude with one (gis::GeoreferencedGeoJson).
StatusOr<nlohmann::json> GeoJsonToWrite(nlohmann::json collection,
                                        const std::optional<gis::GeoOrigin>& origin);

}  // namespace fleetmap::cli
