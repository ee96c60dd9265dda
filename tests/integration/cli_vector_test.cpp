// Runs the real `fleetmap` binary through the vector-map subcommands: vectorize -> validate ->
// rasterize -> compare, render, bench vectorize, and every bad input (exit code 2, file named).

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/grid/map_io.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/vmap_file.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using testing::RunFleetmap;

// A fresh directory per test and process, so parallel ctest runs never share files.
std::string TestDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                                    ("cli_vector_" + std::to_string(getpid())) / info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// A 15 x 12.5 m room at 0.05 m (so it spans several 10 m tiles, and walls cross tile borders):
// unknown outside, a wall 2 cells thick, free inside, a 6 x 6 pillar, a short 1-cell wall, and an
// isolated occupied cell.
grid::OccupancyGrid Room() {
  grid::OccupancyGrid grid(300, 250, 0.05, Pose2{-2.5, -1.0, 0.0});
  for (int y = 10; y < 240; ++y) {
    for (int x = 10; x < 290; ++x) {
      const bool wall = x < 12 || y < 12 || x >= 288 || y >= 238;
      grid.at(x, y) = wall ? grid::kOccupiedValue : grid::kFreeValue;
    }
  }
  for (int y = 100; y < 106; ++y) {
    for (int x = 200; x < 206; ++x) grid.at(x, y) = grid::kOccupiedValue;
  }
  for (int x = 12; x < 80; ++x) grid.at(x, 150) = grid::kOccupiedValue;
  grid.at(150, 60) = grid::kOccupiedValue;
  return grid;
}

std::string Save(const grid::OccupancyGrid& grid, const std::string& dir, const std::string& name) {
  const std::string path = dir + "/" + name + ".yaml";
  const Status status = grid::SaveMap(grid, path);
  EXPECT_TRUE(status.ok()) << status;
  return path;
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(CliVectorTest, VectorizeValidateRasterizeCompareRoundTrip) {
  const std::string dir = TestDir();
  const std::string map = Save(Room(), dir, "room");
  const std::string vmap = dir + "/room.vmap";

  process::CommandResult run = RunFleetmap({"vectorize", map, "-o", vmap, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_GT(summary["vertices"].get<int>(), 0);
  EXPECT_GT(summary["segments"].get<int>(), 0);
  EXPECT_GT(summary["free_vertices"].get<int>(), 0);
  EXPECT_GE(summary["tiles"].get<int>(), 4);  // x from -2.5 to 12.5 m, y from -1 to 11.5 m
  EXPECT_GT(summary["bytes"]["raw"].get<int>(), 0);
  EXPECT_LE(summary["bytes"]["zstd"].get<int>(), summary["bytes"]["raw"].get<int>() + 64);
  EXPECT_GE(summary["ms"].get<double>(), 0.0);
  EXPECT_NEAR(summary["epsilon"].get<double>(), 0.05 * std::sqrt(2.0), 1e-12);

  run = RunFleetmap({"validate", map, vmap, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_TRUE(report["valid"].get<bool>());
  EXPECT_EQ(report["uncovered_points"], 0);
  EXPECT_EQ(report["discontinuous_segments"], 0);
  EXPECT_GT(report["delimitation_points"].get<int>(), 1000);
  EXPECT_LE(report["worst_point_distance"].get<double>(), report["epsilon"].get<double>());
  EXPECT_THAT(RunFleetmap({"validate", map, vmap}).out, HasSubstr("valid"));

  const std::string back = dir + "/back.yaml";
  run = RunFleetmap({"rasterize", vmap, "-o", back, "--like", map});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = RunFleetmap({"compare", back, map, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json scores = nlohmann::json::parse(run.out);
  EXPECT_GE(scores["MS"].get<double>(), 95.0);
  EXPECT_GE(scores["OPDF"].get<double>(), 95.0);
  EXPECT_GE(scores["UPDF"].get<double>(), 95.0);

  // The default geometry: the tiles' bounding box at the .vmap's resolution.
  run = RunFleetmap({"rasterize", vmap, "-o", dir + "/bounds.yaml"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  StatusOr<grid::LoadedMap> bounds = grid::LoadMap(dir + "/bounds.yaml");
  ASSERT_TRUE(bounds.ok()) << bounds.status();
  EXPECT_EQ(bounds->grid.resolution(), 0.05);
  EXPECT_EQ(bounds->grid.origin(), (Pose2{-10.0, -10.0, 0.0}));
  EXPECT_EQ(bounds->grid.width(), 600);  // tiles -1..1
  EXPECT_EQ(bounds->grid.height(), 600);

  // The paper's method writes a .vmap too (its constraints may or may not hold: exit 0 or 1).
  const std::string paper = dir + "/paper.vmap";
  ASSERT_EQ(RunFleetmap({"vectorize", map, "-o", paper, "--method", "paper"}).exit_code, 0);
  EXPECT_LE(RunFleetmap({"validate", map, paper}).exit_code, 1);

  run = RunFleetmap({"compare", map, map});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("MS   100.00 %"));
}

// --free-epsilon trades bytes for fidelity: below a cell it keeps one-cell unknown specks inside
// free space (the default drops their holes, so they come back free) and the free / unknown
// border cell for cell.
TEST(CliVectorTest, FreeEpsilonKeepsUnknownSpecksAtMoreBytes) {
  const std::string dir = TestDir();
  grid::OccupancyGrid room = Room();
  for (int k = 0; k < 20; ++k) room.at(30 + 11 * k, 40 + 7 * (k % 5)) = grid::kUnknownValue;
  const std::string map = Save(room, dir, "specks");
  auto round_trip_ms = [&](const std::vector<std::string>& extra, nlohmann::json* summary) {
    const std::string vmap = dir + "/specks" + std::to_string(extra.size()) + ".vmap";
    std::vector<std::string> args = {"vectorize", map, "-o", vmap, "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    process::CommandResult run = RunFleetmap(args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    *summary = nlohmann::json::parse(run.out);
    const std::string back = dir + "/back" + std::to_string(extra.size()) + ".yaml";
    EXPECT_EQ(RunFleetmap({"rasterize", vmap, "-o", back, "--like", map}).exit_code, 0);
    run = RunFleetmap({"compare", back, map, "--json"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out)["MS"].get<double>();
  };
  nlohmann::json coarse;
  nlohmann::json fine;
  const double coarse_ms = round_trip_ms({}, &coarse);
  const double fine_ms = round_trip_ms({"--free-epsilon", "0.0375"}, &fine);
  EXPECT_NEAR(coarse["free_epsilon"].get<double>(), 0.05 * std::sqrt(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(fine["free_epsilon"].get<double>(), 0.0375);
  // Each speck is a hole of its own now: more free vertices and bytes, 20 more cells right.
  EXPECT_GE(fine["free_vertices"].get<int>(), coarse["free_vertices"].get<int>() + 20 * 3);
  EXPECT_GT(fine["bytes"]["raw"].get<int>(), coarse["bytes"]["raw"].get<int>());
  EXPECT_GE(fine_ms - coarse_ms, 100.0 * 20 / (300 * 250) - 1e-9);
  // The obstacles do not depend on it.
  EXPECT_EQ(fine["vertices"], coarse["vertices"]);
}

TEST(CliVectorTest, ValidateExitsOneOnABrokenVmap) {
  const std::string dir = TestDir();
  const grid::OccupancyGrid room = Room();
  const std::string map = Save(room, dir, "room");
  vector_map::TiledVectorMap broken;
  broken.frame_id = "fleet";
  broken.resolution = 0.05;
  broken.epsilon = 0.05 * std::sqrt(2.0);
  vector_map::VectorMap tile;
  tile.frame_id = "fleet";
  tile.resolution = broken.resolution;
  tile.epsilon = broken.epsilon;
  // In the middle of the free room, metres from any obstacle.
  tile.obstacles.push_back({.points = {Point2(3.0, 3.0), Point2(4.0, 3.5)}});
  broken.tiles.emplace(TileId{0, 0}, tile);
  const std::string vmap = dir + "/broken.vmap";
  ASSERT_TRUE(transport::WriteVmapFile(broken, vmap).ok());

  process::CommandResult run = RunFleetmap({"validate", map, vmap, "--json"});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_FALSE(report["valid"].get<bool>());
  EXPECT_EQ(report["discontinuous_segments"], 1);
  EXPECT_GT(report["uncovered_points"].get<int>(), 0);  // the walls are not drawn at all
  EXPECT_GT(report["worst_segment_distance"].get<double>(), report["epsilon"].get<double>());
  run = RunFleetmap({"validate", map, vmap});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.out, HasSubstr("VIOLATED"));
}

TEST(CliVectorTest, CompareSaysUndefinedForAnAllUnknownMap) {
  const std::string dir = TestDir();
  const grid::OccupancyGrid room = Room();
  const grid::OccupancyGrid unknown(room.width(), room.height(), room.resolution(), room.origin());
  const std::string truth = Save(room, dir, "room");
  const std::string robot = Save(unknown, dir, "unknown");
  process::CommandResult run = RunFleetmap({"compare", robot, truth});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("OPDF undefined"));
  EXPECT_THAT(run.out, HasSubstr("UPDF undefined"));
  run = RunFleetmap({"compare", robot, truth, "--json", "--window", "4"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json scores = nlohmann::json::parse(run.out);
  EXPECT_TRUE(scores["OPDF"].is_null());
  EXPECT_TRUE(scores["UPDF"].is_null());
  EXPECT_TRUE(scores["CC"].is_null());  // a constant map has no standard deviation
  EXPECT_TRUE(scores["MS"].is_number());
  EXPECT_EQ(scores["window"], 4);
}

TEST(CliVectorTest, DegenerateGridsWork) {
  const std::string dir = TestDir();
  struct Case {
    std::string name;
    grid::OccupancyGrid grid;
  };
  const std::vector<Case> cases = {
      {"all_unknown", grid::OccupancyGrid(40, 30, 0.05)},
      {"all_free", grid::OccupancyGrid(40, 30, 0.05, {}, grid::kFreeValue)},
      {"all_occupied", grid::OccupancyGrid(40, 30, 0.05, {}, grid::kOccupiedValue)},
      {"one_occupied", grid::OccupancyGrid(1, 1, 0.05, {}, grid::kOccupiedValue)},
      {"one_free", grid::OccupancyGrid(1, 1, 0.05, {}, grid::kFreeValue)},
      {"one_unknown", grid::OccupancyGrid(1, 1, 0.05)},
  };
  for (const Case& c : cases) {
    const std::string map = Save(c.grid, dir, c.name);
    const std::string vmap = dir + "/" + c.name + ".vmap";
    process::CommandResult run = RunFleetmap({"vectorize", map, "-o", vmap, "--json"});
    ASSERT_EQ(run.exit_code, 0) << c.name << ": " << run.err;
    const nlohmann::json summary = nlohmann::json::parse(run.out);
    run = RunFleetmap({"validate", map, vmap});
    EXPECT_EQ(run.exit_code, 0) << c.name << ": " << run.out << run.err;
    const std::string back = dir + "/" + c.name + "_back.yaml";
    run = RunFleetmap({"rasterize", vmap, "-o", back, "--like", map});
    ASSERT_EQ(run.exit_code, 0) << c.name << ": " << run.err;
    run = RunFleetmap({"compare", back, map, "--json"});
    EXPECT_EQ(run.exit_code, 0) << c.name << ": " << run.err;
    run = RunFleetmap({"render", vmap, "-o", dir + "/" + c.name + ".svg"});
    EXPECT_EQ(run.exit_code, 0) << c.name << ": " << run.err;
    if (c.name.find("unknown") != std::string::npos) {
      EXPECT_EQ(summary["tiles"], 0) << c.name;
      // No tiles, no geometry of its own: rasterizing without --like says so.
      run = RunFleetmap({"rasterize", vmap, "-o", dir + "/x.yaml"});
      EXPECT_EQ(run.exit_code, 2);
      EXPECT_THAT(run.err, HasSubstr(vmap + ": holds no tiles"));
    } else {
      EXPECT_EQ(summary["tiles"], 1) << c.name;
      EXPECT_GT(summary["bytes"]["raw"].get<int>(), 0);
    }
    if (c.name == "all_occupied" || c.name == "one_occupied") {
      EXPECT_GE(summary["vertices"].get<int>(), 1) << c.name;
    }
  }
}

TEST(CliVectorTest, GeoJsonHasTheRequiredStructure) {
  const std::string dir = TestDir();
  const std::string map = Save(Room(), dir, "room");
  const std::string geojson = dir + "/room.geojson";
  const process::CommandResult run =
      RunFleetmap({"vectorize", map, "-o", dir + "/room.vmap", "--geojson", geojson, "--svg",
                   dir + "/room.svg", "--png", dir + "/room.png"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(ReadText(geojson));
  EXPECT_EQ(json["type"], "FeatureCollection");
  EXPECT_NEAR(json["properties"]["epsilon"].get<double>(), 0.05 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(json["properties"]["resolution"].get<double>(), 0.05, 1e-9);
  EXPECT_TRUE(json["properties"]["frame"].is_string());
  int obstacles = 0;
  int free = 0;
  for (const nlohmann::json& feature : json["features"]) {
    EXPECT_EQ(feature["type"], "Feature");
    const std::string kind = feature["properties"]["kind"];
    const std::string type = feature["geometry"]["type"];
    if (kind == "obstacle") {
      ++obstacles;
      const nlohmann::json& coordinates = feature["geometry"]["coordinates"];
      if (type == "Point") {
        EXPECT_EQ(coordinates.size(), 2u);
      } else {
        EXPECT_EQ(type, "LineString");
        EXPECT_GE(coordinates.size(), 2u);
        EXPECT_EQ(coordinates[0].size(), 2u);
      }
      EXPECT_GE(feature["properties"]["half_width"].get<double>(), 0.0);
    } else {
      ++free;
      EXPECT_EQ(kind, "free");
    }
  }
  EXPECT_GT(obstacles, 0);
  EXPECT_GT(free, 0);
  EXPECT_THAT(testing::GeoJsonProblems(json), IsEmpty());
  EXPECT_EQ(ReadText(dir + "/room.svg").rfind("<svg", 0), 0u);
  EXPECT_EQ(ReadText(dir + "/room.png").substr(1, 3), "PNG");
}

// `fleetmap vectorize --geojson` on every real map present (docs/file-formats.md: valid simple
// features, crs EPSG:3857), judged by GEOS and by GDAL (gdal-bin, scripts/install-deps.sh) as a
// GIS user would load the file: no invalid geometry, metres in EPSG:3857. (Subprocess does not
// search PATH: the tools are named by their path.)
TEST(CliVectorTest, GeoJsonOfRealMapsIsValidForGisTools) {
  const std::string ogrinfo = "/usr/bin/ogrinfo";
  ASSERT_TRUE(std::filesystem::exists(ogrinfo)) << "gdal-bin is not installed: make deps";
  int maps = 0;
  for (const char* name : {"intel_lab", "aces3_austin", "nav2_warehouse", "willow_garage_2010",
                           "strands_kth", "aws_small_house", "tb3_world"}) {
    const std::string map = std::string(FLEETMAP_SHARED_MAPS_DIR) + "/" + name + ".yaml";
    if (!std::filesystem::exists(map)) continue;
    ++maps;
    const std::string dir = TestDir();
    const std::string geojson = dir + "/" + name + ".geojson";
    const process::CommandResult run =
        RunFleetmap({"vectorize", map, "-o", dir + "/" + name + ".vmap", "--geojson", geojson});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_THAT(testing::GeoJsonProblems(nlohmann::json::parse(ReadText(geojson))), IsEmpty())
        << name;
    std::string sql = "SELECT COUNT(*) AS invalid FROM ";
    sql.append(name).append(" WHERE NOT ST_IsValid(geometry)");
    const process::CommandResult invalid =
        process::RunCommand({ogrinfo, "-ro", "-q", "-dialect", "SQLite", "-sql", sql, geojson});
    EXPECT_THAT(invalid.out, HasSubstr("invalid (Integer) = 0")) << name << invalid.output();
    const process::CommandResult layer =
        process::RunCommand({ogrinfo, "-ro", "-so", geojson, name});
    EXPECT_THAT(layer.out, HasSubstr("ID[\"EPSG\",3857]")) << name << layer.output();
  }
  EXPECT_GT(maps, 0) << "no real map in " << FLEETMAP_SHARED_MAPS_DIR;
}

TEST(CliVectorTest, RenderDrawsVectorMapsAndGrids) {
  const std::string dir = TestDir();
  const std::string map = Save(Room(), dir, "room");
  const std::string vmap = dir + "/room.vmap";
  ASSERT_EQ(RunFleetmap({"vectorize", map, "-o", vmap}).exit_code, 0);
  for (const auto& [input, output] : std::vector<std::pair<std::string, std::string>>{
           {vmap, "v.svg"}, {vmap, "v.png"}, {map, "g.svg"}, {map, "g.png"}}) {
    const process::CommandResult run = RunFleetmap({"render", input, "-o", dir + "/" + output});
    ASSERT_EQ(run.exit_code, 0) << output << ": " << run.err;
    const std::string bytes = ReadText(dir + "/" + output);
    if (output.ends_with(".svg")) {
      EXPECT_THAT(bytes, HasSubstr("<svg")) << output;
    } else {
      EXPECT_EQ(bytes.substr(1, 3), "PNG") << output;
    }
  }
  EXPECT_EQ(RunFleetmap({"render", vmap, "-o", dir + "/v2.png", "--like", map}).exit_code, 0);
}

TEST(CliVectorTest, BadInputsExitWithCode2AndNameTheFile) {
  const std::string dir = TestDir();
  const std::string map = Save(Room(), dir, "room");
  const std::string small = Save(grid::OccupancyGrid(10, 10, 0.05), dir, "small");
  const std::string vmap = dir + "/room.vmap";
  ASSERT_EQ(RunFleetmap({"vectorize", map, "-o", vmap}).exit_code, 0);
  const std::string bytes = ReadText(vmap);
  const std::string truncated = dir + "/truncated.vmap";
  WriteText(truncated, bytes.substr(0, bytes.size() / 2));
  const std::string corrupt = dir + "/corrupt.vmap";
  WriteText(corrupt, "this is not CDR at all");
  const std::string empty_vmap = dir + "/empty.vmap";
  WriteText(empty_vmap, "");
  grid::OccupancyGrid rotated_grid(20, 20, 0.05, Pose2{0.0, 0.0, 0.5});
  const std::string rotated = Save(rotated_grid, dir, "rotated");
  const std::string zero_size = dir + "/zero.yaml";
  WriteText(zero_size,
            "image: zero.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  WriteText(dir + "/zero.pgm", "P5\n0 0\n255\n");
  const std::string missing = dir + "/missing.yaml";
  const std::string missing_vmap = dir + "/missing.vmap";
  const std::string coarse =
      Save(grid::OccupancyGrid(300, 250, 0.1, {}, grid::kFreeValue), dir, "coarse");

  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> messages;
  };
  const std::vector<Case> cases = {
      {{"vectorize", missing, "-o", vmap}, {missing, "no such file"}},
      {{"vectorize", zero_size, "-o", dir + "/z.vmap"}, {"zero.pgm"}},
      {{"vectorize", map, "-o", vmap, "--epsilon", "nan"}, {map, "--epsilon must be"}},
      {{"vectorize", map, "-o", vmap, "--epsilon", "0"}, {map, "--epsilon must be"}},
      {{"vectorize", map, "-o", vmap, "--epsilon", "-0.1"}, {map, "--epsilon must be"}},
      {{"vectorize", map, "-o", vmap, "--epsilon", "0.001"}, {map, "epsilon"}},
      {{"vectorize", map, "-o", vmap, "--free-epsilon", "0"}, {map, "--free-epsilon must be"}},
      {{"vectorize", map, "-o", vmap, "--free-epsilon", "inf"}, {map, "--free-epsilon must be"}},
      {{"vectorize", map, "-o", vmap, "--tile-size", "nan"}, {map, "--tile-size must be"}},
      {{"vectorize", map, "-o", vmap, "--method", "fancy"}, {map, "unknown --method 'fancy'"}},
      {{"vectorize", map, "-o", vmap, "--max-cells", "1000"}, {"room.pgm", "limit of 1000"}},
      {{"vectorize", rotated, "-o", dir + "/r.vmap"}, {rotated, "rotated"}},
      {{"vectorize", map, "-o", dir + "/no/such/dir/x.vmap"},
       {dir + "/no/such/dir/x.vmap: cannot write: No such file or directory"}},
      {{"validate", map, missing_vmap}, {missing_vmap, "no such file"}},
      {{"validate", missing, vmap}, {missing, "no such file"}},
      {{"validate", map, truncated}, {truncated, "not a valid .vmap"}},
      {{"validate", map, corrupt}, {corrupt, "not a valid .vmap"}},
      {{"validate", map, empty_vmap}, {empty_vmap}},
      {{"validate", coarse, vmap}, {vmap, "resolution", coarse}},
      {{"rasterize", truncated, "-o", dir + "/t.yaml"}, {truncated, "not a valid .vmap"}},
      {{"rasterize", vmap, "-o", dir + "/t.yaml", "--resolution", "nan"}, {vmap, "--resolution"}},
      {{"rasterize", vmap, "-o", dir + "/t.yaml", "--resolution", "0.0001", "--max-cells", "1000"},
       {vmap, "--max-cells"}},
      {{"rasterize", vmap, "-o", dir + "/t.yaml", "--like", missing}, {missing, "no such file"}},
      {{"compare", map, small}, {"sizes do not match", map, small}},
      {{"compare", missing, map}, {missing, "no such file"}},
      {{"compare", map, map, "--window", "0"}, {map, "--window"}},
      {{"render", corrupt, "-o", dir + "/c.svg"}, {corrupt, "not a valid .vmap"}},
      {{"render", map, "-o", dir + "/c.gif"}, {"c.gif", "expected .svg or .png"}},
      {{"render", dir + "/room.txt", "-o", dir + "/c.png"}, {"room.txt", "unknown input"}},
      {{"render", map, "-o", dir + "/no/such/dir/c.png"},
       {dir + "/no/such/dir/c.png: cannot write: No such file or directory"}},
      {{"bench", "vectorize", "--maps", dir + "/nowhere"}, {dir + "/nowhere", "no such directory"}},
      {{"bench", "vectorize", "--maps", dir, "--runs", "3"}, {"--runs must be >= 5"}},
  };
  for (const Case& c : cases) {
    const process::CommandResult run = RunFleetmap(c.args);
    const std::string label = ::testing::PrintToString(c.args);
    EXPECT_EQ(run.exit_code, 2) << label << "\n" << run.out << run.err;
    EXPECT_EQ(run.out, "") << label;
    for (const std::string& message : c.messages) {
      EXPECT_THAT(run.err, HasSubstr(message)) << label;
    }
  }
}

TEST(CliVectorTest, BenchVectorizeSkipsACorruptMapAndMeasuresTheRest) {
  const std::string dir = TestDir();
  std::filesystem::create_directories(dir + "/maps");
  Save(Room(), dir + "/maps", "room");
  const std::string broken = dir + "/maps/broken.yaml";
  WriteText(broken, "image: broken.pgm\nresolution: 0.05\n");  // no origin, no image
  const std::string json_path = dir + "/bench.json";
  const process::CommandResult run =
      RunFleetmap({"bench", "vectorize", "--maps", dir + "/maps", "--json", json_path});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr(broken));
  EXPECT_THAT(run.err, HasSubstr("1 of 2 maps skipped"));
  EXPECT_THAT(run.out, HasSubstr("| room |"));
  EXPECT_THAT(run.out, Not(HasSubstr("| broken |")));
  const nlohmann::json json = nlohmann::json::parse(ReadText(json_path));
  ASSERT_EQ(json["maps"].size(), 1u);
  EXPECT_EQ(json["maps"][0]["name"], "room");
}

TEST(CliVectorTest, BenchVectorizeWritesTablesJsonAndCsv) {
  const std::string dir = TestDir();
  std::filesystem::create_directories(dir + "/maps");
  Save(Room(), dir + "/maps", "room");
  const std::string json_path = dir + "/bench.json";
  const std::string csv_path = dir + "/bench.csv";
  const process::CommandResult run = RunFleetmap(
      {"bench", "vectorize", "--maps", dir + "/maps", "--json", json_path, "--csv", csv_path});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("| room |"));
  EXPECT_THAT(run.out, HasSubstr("sum / median"));
  EXPECT_THAT(run.out, HasSubstr("| target |"));
  const nlohmann::json json = nlohmann::json::parse(ReadText(json_path));
  ASSERT_EQ(json["maps"].size(), 1u);
  const nlohmann::json& room = json["maps"][0];
  EXPECT_EQ(room["name"], "room");
  EXPECT_TRUE(room["ours_obstacles"]["valid"].get<bool>());
  EXPECT_TRUE(room["ours_full"]["valid"].get<bool>());
  EXPECT_TRUE(room["vmap"]["valid"].get<bool>());
  EXPECT_GT(room["opencv"]["vertices"].get<int>(), 0);
  EXPECT_GT(room["grid"]["zstd"].get<int>(), 0);
  // Bytes per fleet tile: the same tiles on both sides, every baseline named, zstd -19 of a tile
  // smaller than the tile's patch.
  const nlohmann::json& tile_bytes = room["tile_bytes"];
  EXPECT_EQ(tile_bytes["grid_tiles"], room["vmap"]["tiles"]);
  EXPECT_EQ(tile_bytes["vector_tiles"], room["vmap"]["tiles"]);
  EXPECT_GT(tile_bytes["vector"].get<int>(), 0);
  EXPECT_LT(tile_bytes["grid"]["zstd19"].get<int>(), tile_bytes["grid"]["patch_cdr"].get<int>());
  ASSERT_EQ(tile_bytes["vector_over"].size(), 4u);
  EXPECT_EQ(tile_bytes["vector_over"][2]["baseline"], "zstd -19");
  EXPECT_DOUBLE_EQ(tile_bytes["vector_over"][2]["ratio"].get<double>(),
                   tile_bytes["vector"].get<double>() / tile_bytes["grid"]["zstd19"].get<double>());
  EXPECT_EQ(json["tile_bytes_headline"]["worst_map"], "room");
  EXPECT_THAT(run.out, HasSubstr("| vector / zstd -19 |"));
  EXPECT_THAT(run.out, HasSubstr("Vector tiles / smallest baseline"));
  EXPECT_THAT(run.out, HasSubstr("| vector tiles <= 0.5 x grid zstd -19 tiles"));
  EXPECT_TRUE(room["round_trip"]["MS"].is_number());
  EXPECT_EQ(room["revectorize_tile"]["changed_cells"], 5);
  // Every tile with known cells is timed once, the busiest among them.
  const nlohmann::json& every_tile = room["revectorize_tile"]["every_tile"];
  EXPECT_EQ(every_tile.size(), room["vmap"]["tiles"].get<size_t>());
  EXPECT_TRUE(std::any_of(every_tile.begin(), every_tile.end(), [&](const nlohmann::json& t) {
    return t["tile"] == room["revectorize_tile"]["tile"] && t["ms"].get<double>() > 0.0;
  }));
  EXPECT_LE(room["revectorize_tile"]["tiles_within_1ms"].get<size_t>(), every_tile.size());
  EXPECT_FALSE(json["targets"].empty());

  // Where the vertices go: the room's components are the walls (with the attached shelf line,
  // over 50 cells), the 6 x 6 block (11-50) and the speck (1); every vertex is counted once.
  EXPECT_THAT(run.out, HasSubstr("Where the vertices go"));
  const nlohmann::json& classes = room["vertices_by_component"]["classes"];
  ASSERT_EQ(classes.size(), 5u);
  const std::vector<int> components = {1, 0, 0, 1, 1};
  int ours_sum = 0;
  int opencv_sum = 0;
  for (size_t c = 0; c < classes.size(); ++c) {
    EXPECT_EQ(classes[c]["components"].get<int>(), components[c]) << classes[c];
    ours_sum += classes[c]["ours_vertices"].get<int>();
    opencv_sum += classes[c]["opencv_vertices"].get<int>();
  }
  EXPECT_EQ(classes[0]["component_cells"], "1");
  EXPECT_EQ(classes[4]["component_cells"], ">50");
  EXPECT_EQ(classes[0]["ours_vertices"].get<int>(), 1);  // the speck is a point obstacle
  EXPECT_EQ(classes[0]["opencv_vertices"].get<int>(), 1);
  EXPECT_EQ(room["vertices_by_component"]["ours_unattributed"].get<int>(), 0);
  EXPECT_EQ(ours_sum, room["ours_obstacles"]["vertices"].get<int>());
  EXPECT_EQ(opencv_sum, room["opencv"]["vertices"].get<int>());

  const std::string csv = ReadText(csv_path);
  EXPECT_EQ(csv.rfind("map,cells,", 0), 0u);
  EXPECT_THAT(csv, HasSubstr(",vector_over_zstd19,"));
  EXPECT_THAT(csv, HasSubstr("\nroom,"));
}

}  // namespace
}  // namespace fleetmap::cli
