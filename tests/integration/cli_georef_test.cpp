// `--georef LAT LON YAW` on the commands that write GeoJSON, with the real binary: the file is
// RFC 7946 WGS84 (no crs member, [longitude, latitude] near the surveyed place), a vertex lands
// where PROJ's `geod` tool puts it, areas match the frame-metre export (geodesic areas, and
// SpatiaLite's on the ellipsoid through GDAL), GDAL's ogrinfo opens it as EPSG:4326, and bad values
// exit 2 naming the option.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/process/subprocess.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap {
namespace {

using testing::GeoJsonCoordinates;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using testing::RunFleetmap;

// The Eiffel Tower's surveyed place, with the frame's x axis 30 degrees north of East.
constexpr double kLatitude = 48.8583;
constexpr double kLongitude = 2.2945;
constexpr double kYaw = 30.0;
const std::vector<std::string> kGeoref = {"--georef", "48.8583", "2.2945", "30"};

const std::string kHouse = std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml";
const std::string kOgrinfo = "/usr/bin/ogrinfo";

nlohmann::json ReadJson(const std::string& path) {
  return nlohmann::json::parse(testing::ReadFile(path));
}

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Calls `visit` with every position of every feature's geometry.
template <typename Visit>
void ForEachPosition(const nlohmann::json& coordinates, const Visit& visit) {
  if (coordinates.is_array() && !coordinates.empty() && coordinates[0].is_number()) {
    visit(coordinates[0].get<double>(), coordinates[1].get<double>());
    return;
  }
  for (const nlohmann::json& part : coordinates) ForEachPosition(part, visit);
}

// The length of every polygon ring of a frame-metre collection, in metres.
double PolygonPerimeter(const nlohmann::json& plane) {
  double length = 0.0;
  const auto add_rings = [&](const nlohmann::json& rings) {
    for (const nlohmann::json& ring : rings) {
      for (size_t i = 0; i + 1 < ring.size(); ++i) {
        length += std::hypot(ring[i + 1][0].get<double>() - ring[i][0].get<double>(),
                             ring[i + 1][1].get<double>() - ring[i][1].get<double>());
      }
    }
  };
  for (const nlohmann::json& feature : plane["features"]) {
    const nlohmann::json& geometry = feature["geometry"];
    if (geometry["type"] == "Polygon") add_rings(geometry["coordinates"]);
    if (geometry["type"] == "MultiPolygon") {
      for (const nlohmann::json& polygon : geometry["coordinates"]) add_rings(polygon);
    }
  }
  return length;
}

// The most the area of a collection can change when its positions are rounded to 1e-8 degree:
// each vertex moves by at most half a step in each coordinate (0.56 mm of latitude, less of
// longitude), so each edge by at most 0.8 mm across itself.
double RoundingAreaBound(const nlohmann::json& plane) { return 0.0008 * PolygonPerimeter(plane); }

// The frame-metre and the WGS84 export of the same map agree where they should: no crs, nothing
// GIS tools would refuse, every position within a few hundred metres of the surveyed place, and
// the same area but for rounding (RoundingAreaBound).
void ExpectSameMapOnEarth(const nlohmann::json& plane, const nlohmann::json& wgs84, double latitude,
                          double longitude) {
  EXPECT_FALSE(wgs84.contains("crs")) << "RFC 7946 has no crs member";
  EXPECT_THAT(testing::GeoJsonProblems(plane), IsEmpty());
  EXPECT_THAT(testing::GeoJsonProblems(wgs84, GeoJsonCoordinates::kWgs84), IsEmpty());
  int positions = 0;
  for (const nlohmann::json& feature : wgs84["features"]) {
    ForEachPosition(feature["geometry"]["coordinates"], [&](double lon, double lat) {
      ++positions;
      EXPECT_NEAR(lon, longitude, 0.005);
      EXPECT_NEAR(lat, latitude, 0.005);
    });
  }
  EXPECT_GT(positions, 0);
  const double plane_area = testing::PolygonArea(plane, GeoJsonCoordinates::kFrameMetres);
  EXPECT_GT(plane_area, 1.0);
  EXPECT_NEAR(testing::PolygonArea(wgs84, GeoJsonCoordinates::kWgs84), plane_area,
              RoundingAreaBound(plane));
  EXPECT_LT(RoundingAreaBound(plane), 0.01 * plane_area) << "a bound that tells something";
}

// Where PROJ's `geod` (the direct geodesic problem on WGS84) puts the frame point (x, y): at its
// distance from the origin, at the azimuth (clockwise from North) its direction has.
std::pair<double, double> GeodLonLat(double x, double y) {
  const double azimuth = 90.0 - (kYaw + std::atan2(y, x) * 180.0 / std::numbers::pi);
  std::ostringstream line;
  line.precision(17);
  line << kLatitude << " " << kLongitude << " " << azimuth << " " << std::hypot(x, y);
  const process::CommandResult geod = process::RunCommand(
      {"/bin/sh", "-c", "echo '" + line.str() + "' | /usr/bin/geod +ellps=WGS84 -f %.12f"});
  EXPECT_EQ(geod.exit_code, 0) << geod.output() << " (geod is in proj-bin: make deps)";
  std::istringstream columns(geod.out);
  double lat = 0.0, lon = 0.0;
  columns >> lat >> lon;
  return {lon, lat};
}

// `ogrinfo` run read-only on `file`; an SQL query in SQLite's dialect (SpatiaLite's functions).
process::CommandResult Ogrinfo(const std::vector<std::string>& args) {
  EXPECT_TRUE(std::filesystem::exists(kOgrinfo)) << "gdal-bin is not installed: make deps";
  return process::RunCommand(Concat({kOgrinfo, "-ro"}, args));
}

process::CommandResult OgrSql(const std::string& sql, const std::string& file) {
  return Ogrinfo({"-q", "-dialect", "SQLite", "-sql", sql, file});
}

// The house vectorized into `dir`, in frame metres (plane.geojson) and with --georef
// (house.geojson).
void VectorizeHouse(const std::string& dir) {
  const process::CommandResult plane = RunFleetmap(
      {"vectorize", kHouse, "-o", dir + "/plane.vmap", "--geojson", dir + "/plane.geojson"});
  ASSERT_EQ(plane.exit_code, 0) << plane.output();
  const process::CommandResult placed = RunFleetmap(
      Concat({"vectorize", kHouse, "-o", dir + "/house.vmap", "--geojson", dir + "/house.geojson"},
             kGeoref));
  ASSERT_EQ(placed.exit_code, 0) << placed.output();
}

TEST(CliGeorefTest, AVectorizedMapIsWgs84AtTheSurveyedPlace) {
  const std::string dir = testing::FreshTempDir("cli_georef_vectorize");
  ASSERT_NO_FATAL_FAILURE(VectorizeHouse(dir));
  const nlohmann::json plane = ReadJson(dir + "/plane.geojson");
  const nlohmann::json wgs84 = ReadJson(dir + "/house.geojson");
  ExpectSameMapOnEarth(plane, wgs84, kLatitude, kLongitude);
  EXPECT_EQ(wgs84["properties"]["georeference"],
            nlohmann::json({{"latitude", kLatitude}, {"longitude", kLongitude}, {"yaw", kYaw}}));
  EXPECT_EQ(wgs84["properties"]["frame"], plane["properties"]["frame"]);

  // Obstacles come first and one for one (only free space may split): each vertex of the first
  // walls is where geod puts it, to the rounding of 8 decimals.
  int compared = 0;
  for (size_t i = 0; i < 5 && i < plane["features"].size(); ++i) {
    const nlohmann::json& metres = plane["features"][i];
    const nlohmann::json& degrees = wgs84["features"][i];
    ASSERT_EQ(metres["properties"]["kind"], "obstacle");
    ASSERT_EQ(degrees["geometry"]["type"], metres["geometry"]["type"]);
    EXPECT_EQ(degrees["properties"], metres["properties"]);  // half widths stay metres
    std::vector<std::pair<double, double>> frame_points;
    ForEachPosition(metres["geometry"]["coordinates"],
                    [&](double x, double y) { frame_points.emplace_back(x, y); });
    size_t k = 0;
    ForEachPosition(degrees["geometry"]["coordinates"], [&](double lon, double lat) {
      ASSERT_LT(k, frame_points.size());
      const auto [geod_lon, geod_lat] = GeodLonLat(frame_points[k].first, frame_points[k].second);
      EXPECT_NEAR(lon, geod_lon, 1e-8) << "feature " << i << " vertex " << k;
      EXPECT_NEAR(lat, geod_lat, 1e-8) << "feature " << i << " vertex " << k;
      ++k;
      ++compared;
    });
  }
  EXPECT_GT(compared, 4);
  std::filesystem::remove_all(dir);
}

// Issue 33: the georeferenced GeoJSON opened by ogrinfo with EPSG:4326.
TEST(CliGeorefTest, OgrinfoOpensItAsEpsg4326WithItsFeaturesAndArea) {
  const std::string dir = testing::FreshTempDir("cli_georef_ogrinfo");
  ASSERT_NO_FATAL_FAILURE(VectorizeHouse(dir));
  const std::string file = dir + "/house.geojson";
  const nlohmann::json wgs84 = ReadJson(file);

  const process::CommandResult summary = Ogrinfo({"-so", file, "house"});
  ASSERT_EQ(summary.exit_code, 0) << summary.output();
  EXPECT_THAT(summary.out, HasSubstr("GEOGCRS[\"WGS 84\""));
  EXPECT_THAT(summary.out, HasSubstr("ID[\"EPSG\",4326]"));
  EXPECT_THAT(summary.out,
              HasSubstr("Feature Count: " + std::to_string(wgs84["features"].size()) + "\n"));
  std::smatch extent;
  ASSERT_TRUE(std::regex_search(
      summary.out, extent,
      std::regex(R"(Extent: \(([-0-9.]+), ([-0-9.]+)\) - \(([-0-9.]+), ([-0-9.]+)\))")))
      << summary.out;
  for (int i : {1, 3}) EXPECT_NEAR(std::stod(extent[i]), kLongitude, 0.005) << summary.out;
  for (int i : {2, 4}) EXPECT_NEAR(std::stod(extent[i]), kLatitude, 0.005) << summary.out;

  // Each geometry type GDAL sees, counted as the file has them.
  std::map<std::string, int> types;
  for (const nlohmann::json& feature : wgs84["features"]) {
    std::string type = feature["geometry"]["type"];
    for (char& c : type) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    ++types[type];
  }
  EXPECT_GT(types["LINESTRING"], 0);
  EXPECT_GT(types["POLYGON"] + types["MULTIPOLYGON"], 0);
  for (const auto& [type, count] : types) {
    const process::CommandResult counted = OgrSql(
        "SELECT COUNT(*) AS n FROM house WHERE ST_GeometryType(geometry) = '" + type + "'", file);
    EXPECT_THAT(counted.out, HasSubstr("n (Integer) = " + std::to_string(count) + "\n"))
        << type << ": " << counted.output();
  }
  const process::CommandResult invalid =
      OgrSql("SELECT COUNT(*) AS invalid FROM house WHERE NOT ST_IsValid(geometry)", file);
  EXPECT_THAT(invalid.out, HasSubstr("invalid (Integer) = 0")) << invalid.output();

  // SpatiaLite's area on the WGS84 ellipsoid, against the plane's in metres.
  const nlohmann::json plane = ReadJson(dir + "/plane.geojson");
  const double plane_area = testing::PolygonArea(plane, GeoJsonCoordinates::kFrameMetres);
  const process::CommandResult area = OgrSql(
      "SELECT SUM(ST_Area(geometry, 1)) AS area FROM house WHERE "
      "ST_GeometryType(geometry) IN ('POLYGON', 'MULTIPOLYGON')",
      file);
  std::smatch value;
  ASSERT_TRUE(std::regex_search(area.out, value, std::regex(R"(area \(Real\) = ([0-9.]+))")))
      << area.output();
  EXPECT_NEAR(std::stod(value[1]), plane_area, RoundingAreaBound(plane));
  std::filesystem::remove_all(dir);
}

TEST(CliGeorefTest, TerrainAndExtrapolateWriteWgs84Too) {
  const std::string dir = testing::FreshTempDir("cli_georef_others");
  const std::vector<std::string> terrain = {"terrain", "--kind", "office", "--size",
                                            "20",      "--seed", "3"};
  ASSERT_EQ(RunFleetmap(Concat(terrain, {"-o", dir + "/t.yaml", "--geojson", dir + "/t.geojson"}))
                .exit_code,
            0);
  const process::CommandResult placed_terrain =
      RunFleetmap(Concat(terrain, {"-o", dir + "/s.yaml", "--geojson", dir + "/s.geojson",
                                   "--georef", "-33.45", "-70.66", "-90"}));
  ASSERT_EQ(placed_terrain.exit_code, 0) << placed_terrain.output();
  ExpectSameMapOnEarth(ReadJson(dir + "/t.geojson"), ReadJson(dir + "/s.geojson"), -33.45, -70.66);

  const std::string data = std::string(FLEETMAP_TEST_DATA_DIR) + "/extrapolation/";
  const std::vector<std::string> extrapolate = {"extrapolate", "--map", data + "corridor.yaml",
                                                "--entities", data + "entities.json"};
  ASSERT_EQ(RunFleetmap(Concat(extrapolate, {"--out", dir + "/plane"})).exit_code, 0);
  const process::CommandResult placed_prediction = RunFleetmap(
      Concat(extrapolate, {"--out", dir + "/placed", "--georef", "60.17", "24.94", "135"}));
  ASSERT_EQ(placed_prediction.exit_code, 0) << placed_prediction.output();
  ExpectSameMapOnEarth(ReadJson(dir + "/plane/pth_0.50/predicted_free.geojson"),
                       ReadJson(dir + "/placed/pth_0.50/predicted_free.geojson"), 60.17, 24.94);
  std::filesystem::remove_all(dir);
}

// Every command that writes GeoJSON refuses bad values before doing anything: exit 2, the option
// and the value named.
TEST(CliGeorefTest, BadValuesExit2NamingTheOption) {
  const std::string dir = testing::FreshTempDir("cli_georef_bad");
  const std::string data = std::string(FLEETMAP_TEST_DATA_DIR) + "/extrapolation/";
  const std::vector<std::vector<std::string>> commands = {
      {"vectorize", kHouse, "-o", dir + "/x.vmap", "--geojson", dir + "/x.geojson"},
      {"terrain", "-o", dir + "/t.yaml", "--geojson", dir + "/t.geojson"},
      {"extrapolate", "--map", data + "corridor.yaml", "--entities", data + "entities.json",
       "--out", dir + "/e"},
      {"save-map", "-o", dir + "/m.yaml", "--geojson", dir + "/m.geojson", "--timeout", "1",
       "--localhost-only"},
  };
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"91", "0", "0"}, "latitude 91 is outside [-90, 90] degrees"},
      {{"-90.5", "0", "0"}, "latitude -90.5 is outside [-90, 90] degrees"},
      {{"0", "-181", "0"}, "longitude -181 is outside [-180, 180] degrees"},
      {{"0", "180.5", "0"}, "longitude 180.5 is outside [-180, 180] degrees"},
      {{"north", "0", "0"}, "latitude 'north' is not a number"},
      {{"0", "2.5e", "0"}, "longitude '2.5e' is not a number"},
      {{"nan", "0", "0"}, "latitude nan is not a finite number"},
      {{"0", "0", "inf"}, "yaw inf is not a finite number"},
      {{"1", "2"}, "3 required"},
  };
  for (const std::vector<std::string>& command : commands) {
    for (const auto& [values, message] : bad) {
      const process::CommandResult run =
          RunFleetmap(Concat(Concat(command, {"--georef"}), values), std::chrono::seconds(30));
      EXPECT_EQ(run.exit_code, 2) << command[0] << " " << message << ": " << run.output();
      EXPECT_THAT(run.err, HasSubstr("fleetmap " + command[0] + ": --georef")) << run.err;
      EXPECT_THAT(run.err, HasSubstr(message)) << command[0];
    }
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "nothing written";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fleetmap
