#include "cli/georef_option.hpp"

#include <cmath>
#include <cstdlib>
#include <vector>

#include "common/gis/georeferenced_geojson.hpp"

namespace fleetmap::cli {
namespace {

constexpr char kName[] = "--georef";

// strtod over the whole text; CLI11 would take "12abc" as 12.
double Number(const std::string& text, const char* what) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    throw CLI::ValidationError(
        kName, std::string(what) + " '" + text + "' is not a number (give LAT LON YAW in degrees)");
  }
  return value;
}

}  // namespace

CLI::Option* AddGeorefOption(CLI::App* command, const std::string& frame,
                             std::optional<gis::GeoOrigin>* origin) {
  const std::string help =
      "LAT LON YAW: the " + frame +
      " frame's origin is at WGS84 latitude LAT, longitude LON (degrees) and its x axis points "
      "YAW degrees counter-clockwise from East (0: x East, 90: x North); write the GeoJSON in "
      "WGS84 longitude/latitude (RFC 7946) instead of frame metres";
  // Parsed here, not by CLI11, so that every refusal says which of the three values is wrong.
  CLI::Option* option = command->add_option(
      kName,
      [origin](const CLI::results_t& values) {
        gis::GeoOrigin given;
        given.latitude = Number(values.at(0), "latitude");
        given.longitude = Number(values.at(1), "longitude");
        given.yaw = Number(values.at(2), "yaw");
        if (const Status valid = given.Validate(); !valid.ok()) {
          throw CLI::ValidationError(kName, valid.message());
        }
        *origin = given;
        return true;
      },
      help);
  option->expected(3)->delimiter(',')->type_name("DEGREES")->allow_extra_args(false);
  return option;
}

StatusOr<nlohmann::json> GeoJsonToWrite(nlohmann::json collection,
                                        const std::optional<gis::GeoOrigin>& origin) {
  if (!origin) return collection;
  FLEETMAP_ASSIGN_OR_RETURN(const gis::Georeference georeference,
                            gis::Georeference::Create(*origin));
  return gis::GeoreferencedGeoJson(collection, georeference);
}

}  // namespace fleetmap::cli
