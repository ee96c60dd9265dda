// `fleetmap extrapolate` end to end: outputs, skipped entries, bad input, detection from a cloud.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/extrapolation/ply_reader.hpp"
#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "common/sim/depth_sensor.hpp"
#include "common/sim/indoor_scene_generator.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using testing::RunFleetmap;

std::string Data(const std::string& name) {
  return std::string(FLEETMAP_TEST_DATA_DIR) + "/extrapolation/" + name;
}

std::string TempDir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/cli_extrapolate_" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return nlohmann::json::parse(text.str());
}

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(CliExtrapolateTest, WritesGraphGridsGeoJsonAndOverlayPerThreshold) {
  const std::string out = TempDir("outputs");
  const process::CommandResult run =
      RunFleetmap({"extrapolate", "--map", Data("corridor.yaml"), "--entities",
                   Data("entities.json"), "--out", out, "--pth", "0.5,0.7"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("1 doors, 1 stairs, 1 people"));
  for (const char* p : {"pth_0.50", "pth_0.70"}) {
    const std::string dir = out + "/" + p;
    const nlohmann::json graph = ReadJson(dir + "/graph.json");
    ASSERT_EQ(graph["submaps"].size(), 3u) << p;
    EXPECT_EQ(graph["submaps"][0]["kind"], "observed");
    EXPECT_EQ(graph["submaps"][1]["kind"], "predicted_door");
    EXPECT_EQ(graph["submaps"][2]["kind"], "predicted_stairs");
    EXPECT_EQ(graph["submaps"][2]["elevation"], 3.0);
    ASSERT_EQ(graph["edges"].size(), 2u);
    EXPECT_EQ(graph["edges"][0]["entity"], "door_1");
    for (const char* f : {"overlay.png", "predicted_free.pgm", "extrapolated.yaml", "submap_1.yaml",
                          "submap_2.pgm"}) {
      EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << dir << "/" << f;
    }
    // The predicted free space reads back as a map with free cells, all behind the door.
    const auto predicted = grid::LoadMap(dir + "/predicted_free.yaml");
    ASSERT_TRUE(predicted.ok()) << predicted.status();
    int64_t free = 0;
    for (int y = 0; y < predicted->grid.height(); ++y) {
      for (int x = 0; x < predicted->grid.width(); ++x) {
        if (predicted->grid.StateAt(x, y) != grid::CellState::kFree) continue;
        ++free;
        EXPECT_GT(predicted->grid.CellCenter(x, y).y(), 2.2);
      }
    }
    EXPECT_GT(free, 50);
    const nlohmann::json geojson = ReadJson(dir + "/predicted_free.geojson");
    EXPECT_EQ(geojson["type"], "FeatureCollection");
    EXPECT_THAT(testing::GeoJsonProblems(geojson), IsEmpty()) << p;
    bool door_polygon = false;
    for (const nlohmann::json& f : geojson["features"]) {
      door_polygon |= f["properties"]["class"] == "quasi-static";
    }
    EXPECT_TRUE(door_polygon);
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/entities.json"));
}

TEST(CliExtrapolateTest, SkipsUnusableEntriesWithWarningsAndUsesTheRest) {
  const std::string out = TempDir("skips");
  const process::CommandResult run =
      RunFleetmap({"extrapolate", "--map", Data("corridor.yaml"), "--entities",
                   Data("entities_bad_entries.json"), "--out", out});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* id : {"lift_1", "door_flat", "stairs_x", "person_once"}) {
    EXPECT_THAT(run.err, HasSubstr(id));
  }
  EXPECT_THAT(run.err, HasSubstr("unknown class 'elevator'"));
  const nlohmann::json graph = ReadJson(out + "/pth_0.50/graph.json");
  EXPECT_EQ(graph["submaps"].size(), 2u);  // door_1, oriented from the map
}

TEST(CliExtrapolateTest, BadInputExitsWithTwoNamingTheFile) {
  const std::string dir = TempDir("bad");
  WriteText(dir + "/not.json", "{\"entities\": [");
  WriteText(dir + "/nan.json", "{\"entities\": [{\"class\": \"door\", \"hinge\": [NaN, 0]}]}");
  WriteText(dir + "/bad.ply", "ply\nformat binary_big_endian 1.0\nend_header\n");
  WriteText(dir + "/huge.ply",
            "ply\nformat ascii 1.0\nelement vertex 999999999\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n");
  struct Case {
    std::vector<std::string> args;
    std::string names;
  };
  const std::string map = Data("corridor.yaml"), entities = Data("entities.json");
  const std::vector<Case> cases = {
      {{"--map", dir + "/missing.yaml", "--entities", entities}, "missing.yaml"},
      {{"--map", map, "--entities", dir + "/missing.json"}, "missing.json"},
      {{"--map", map, "--entities", dir + "/not.json"}, "not.json"},
      {{"--map", map, "--entities", dir + "/nan.json"}, "nan.json"},
      {{"--map", map, "--entities", entities, "--cloud", dir + "/bad.ply"}, "bad.ply"},
      {{"--map", map, "--entities", entities, "--cloud", dir + "/huge.ply"}, "huge.ply"},
      {{"--map", map, "--entities", entities, "--pth", "1.5"}, "--pth"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"extrapolate", "--out", dir + "/out"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const process::CommandResult run = RunFleetmap(args);
    EXPECT_EQ(run.exit_code, 2) << c.names << ": " << run.err;
    EXPECT_THAT(run.err, HasSubstr(c.names));
  }
}

TEST(CliExtrapolateTest, EmptyCloudIsAWarning) {
  const std::string dir = TempDir("empty");
  ASSERT_TRUE(extrapolation::WritePly({}, dir + "/empty.ply").ok());
  const process::CommandResult run =
      RunFleetmap({"extrapolate", "--map", Data("corridor.yaml"), "--entities",
                   Data("entities.json"), "--cloud", dir + "/empty.ply", "--out", dir + "/out"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("empty.ply: the point cloud is empty"));
}

TEST(CliExtrapolateTest, DetectsStairsAndDoorsInACloud) {
  const std::string dir = TempDir("cloud");
  sim::IndoorSceneOptions options;
  options.closed_door_probability = 1.0;
  const sim::IndoorScene scene = sim::GenerateIndoorScene(options, 5);
  const auto truth = sim::RasterizeGroundFloor(scene, 0.05, true);
  ASSERT_TRUE(truth.ok());
  ASSERT_TRUE(grid::SaveMap(*truth, dir + "/floor.yaml").ok());
  const auto camera = sim::DepthSensor::Create({});
  ASSERT_TRUE(camera.ok());
  sim::Random random(5);
  // One view of the stairs and one of the first door, from the corridor, merged. (The "local
  // map" is the floor's truth here: it cannot tell which side of a door is unseen, so the door
  // view's --viewpoint orients the doors.)
  const double yc = 0.5 * (scene.corridor_min.y() + scene.corridor_max.y());
  const sim::SceneDoor& door = scene.doors.front();
  const Point2 eye(door.center().x() + 1.8, yc);
  const Vector2 look = door.center() - eye;
  sim::CameraPose door_view, stairs_view;
  door_view.pose = Pose2{eye.x(), eye.y(), std::atan2(look.y(), look.x())};
  stairs_view.pose = Pose2{scene.stairs.foot.x() - 2.5, yc, 0.0};
  extrapolation::PointCloud cloud;
  for (const sim::CameraPose& pose : {door_view, stairs_view}) {
    for (const Eigen::Vector3d& p : camera->Capture(sim::SceneBoxes(scene), pose, &random)) {
      cloud.push_back(p);
    }
  }
  ASSERT_TRUE(extrapolation::WritePly(cloud, dir + "/views.ply").ok());
  WriteText(dir + "/none.json", "{\"entities\": []}");
  const process::CommandResult run =
      RunFleetmap({"extrapolate", "--map", dir + "/floor.yaml", "--entities", dir + "/none.json",
                   "--cloud", dir + "/views.ply", "--viewpoint",
                   std::to_string(eye.x()) + "," + std::to_string(eye.y()), "--out", dir + "/out"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json used = ReadJson(dir + "/out/entities.json");
  int doors = 0, stairs = 0;
  for (const nlohmann::json& e : used["entities"]) {
    if (e["class"] == "door") {
      // The view may show other doors too; one detection must be the door looked at.
      const Point2 centre =
          0.5 * (Point2(e["hinge"][0], e["hinge"][1]) + Point2(e["latch"][0], e["latch"][1]));
      doors += (centre - door.center()).norm() < 0.3;
    }
    if (e["class"] == "stairs") {
      ++stairs;
      EXPECT_LT((Point2(e["position"][0], e["position"][1]) - scene.stairs.foot).norm(), 0.3);
    }
  }
  EXPECT_GE(doors, 1);
  EXPECT_EQ(stairs, 1);
  const nlohmann::json graph = ReadJson(dir + "/out/pth_0.50/graph.json");
  EXPECT_GE(graph["submaps"].size(), 3u);
}

}  // namespace
}  // namespace fleetmap::cli
