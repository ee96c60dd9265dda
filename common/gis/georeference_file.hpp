#pragma once

// The georeference side file `fleetmap save-map --georef` writes beside a map_server YAML
// (docs/file-formats.md, "Georeference side file"): NAME.georef.yaml next to NAME.yaml says where
// the frame of the map's `origin` lies on Earth. The map YAML itself stays exactly what nav2's
// map_server reads; a separate file keeps every map_server reader (nav2, fleetmap info and
// register) unaware of it, where an extra key would be one more thing for each to ignore.

#include <string>

#include "common/gis/georeference.hpp"

namespace fleetmap::gis {

// "maps/fused.yaml" -> "maps/fused.georef.yaml" (the extension, whatever it is, replaced).
std::string GeoreferenceFilePath(const std::string& map_yaml_path);

// The side file's YAML: the map it belongs to (`map_yaml_name`, a file name), the frame the
// origin is given in (`frame`: "fleet" for a fused map), the CRS (EPSG:4326), the origin's
// latitude, longitude and yaw with the yaw's convention, and the PROJ pipeline that takes the
// frame's metres to longitude and latitude.
std::string GeoreferenceFileText(const Georeference& georeference, const std::string& map_yaml_name,
                                 const std::string& frame);

}  // namespace fleetmap::gis
