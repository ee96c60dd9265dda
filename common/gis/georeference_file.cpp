#include "common/gis/georeference_file.hpp"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "common/core/number_format.hpp"

namespace fleetmap::gis {
namespace {

// A YAML double-quoted scalar: a JSON string is one (YAML 1.2 reads JSON's escapes), so any file
// name, with its colons or hashes, reads back as it was.
std::string Quoted(const std::string& text) { return nlohmann::json(text).dump(); }

}  // namespace

std::string GeoreferenceFilePath(const std::string& map_yaml_path) {
  return std::filesystem::path(map_yaml_path).replace_extension(".georef.yaml").string();
}

std::string GeoreferenceFileText(const Georeference& georeference, const std::string& map_yaml_name,
                                 const std::string& frame) {
  const GeoOrigin& origin = georeference.origin();
  std::string text =
      "# Where the frame of the map's origin lies on Earth (fleetmap, docs/file-formats.md,\n"
      "# \"Georeference side file\"). map_server readers do not read this file.\n";
  text.append("map: ").append(Quoted(map_yaml_name)).append("\n");
  text.append("frame: ").append(Quoted(frame)).append("\n");
  text.append("crs: \"EPSG:4326\"  # WGS 84, degrees\n");
  text.append("latitude: ").append(ExactNumber(origin.latitude)).append("\n");
  text.append("longitude: ").append(ExactNumber(origin.longitude)).append("\n");
  text.append("yaw: ")
      .append(ExactNumber(origin.yaw))
      .append("  # degrees counter-clockwise from East to the frame's +x axis (ENU, REP 103)\n");
  text.append("proj_pipeline: ").append(Quoted(georeference.ProjPipeline())).append("\n");
  return text;
}

}  // namespace fleetmap::gis
