// Runs the real `fleetmap learn-objects` and `fleetmap bench objects` and checks outputs and exit
// codes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/grid/map_io.hpp"
#include "common/process/subprocess.hpp"
#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadFile;
using testing::RunFleetmap;

std::string TempDir(const std::string& name) {
  return testing::FreshTempDir("fleetmap_cli_objects_" + name);
}

// A 5 x 5 m room with box outlines (insides unknown) at the given cells.
std::string SaveRoom(const std::string& dir, const std::string& name,
                     const std::vector<std::pair<int, int>>& boxes, int width = 100) {
  grid::OccupancyGrid map(width, 100, 0.05, Pose2{}, grid::kFreeValue);
  for (int i = 0; i < width; ++i) map.at(i, 0) = map.at(i, 99) = grid::kOccupiedValue;
  for (int i = 0; i < 100; ++i) map.at(0, i) = map.at(width - 1, i) = grid::kOccupiedValue;
  for (const auto& [x0, y0] : boxes) {
    for (int y = y0; y < y0 + 8; ++y) {
      for (int x = x0; x < x0 + 12; ++x) {
        const bool edge = x == x0 || y == y0 || x == x0 + 11 || y == y0 + 7;
        map.at(x, y) = edge ? grid::kOccupiedValue : grid::kUnknownValue;
      }
    }
  }
  const std::string path = dir + "/" + name + ".yaml";
  EXPECT_TRUE(grid::SaveMap(map, path).ok());
  return path;
}

TEST(CliObjectsTest, LearnsMovedBoxesAndWritesTheModel) {
  const std::string dir = TempDir("learn");
  const std::string a = SaveRoom(dir, "a", {{10, 10}, {60, 60}});
  const std::string b = SaveRoom(dir, "b", {{30, 70}, {70, 20}});
  const std::string c = SaveRoom(dir, "c", {{15, 50}});
  const process::CommandResult run =
      RunFleetmap({"learn-objects", a, b, c, "--out", dir + "/out", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json model = nlohmann::json::parse(run.out);
  EXPECT_EQ(model, nlohmann::json::parse(ReadFile(dir + "/out/model.json")));
  EXPECT_GE(model["num_objects"].get<int>(), 2);    // two boxes in one map
  EXPECT_EQ(model["num_templates"].get<int>(), 1);  // all boxes alike
  EXPECT_EQ(model["snapshots"].size(), 5u);
  EXPECT_FALSE(model["searched"].empty());
  for (const auto& s : model["snapshots"]) {
    EXPECT_TRUE(s.contains("alignment"));
    EXPECT_TRUE(s["object_pose"].contains("yaw"));
    EXPECT_GE(s["object"].get<int>(), 0);
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/object_0.pgm"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/template_0.pgm"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/montage.png"));
  EXPECT_THAT(run.err, Not(HasSubstr("learn-objects: searching")));  // --json: no progress
  std::filesystem::remove_all(dir);
}

TEST(CliObjectsTest, ShowsProgressOnStderrAndKeepsTheBudget) {
  const std::string dir = TempDir("progress");
  const std::string a = SaveRoom(dir, "a", {{10, 10}, {60, 60}});
  const std::string b = SaveRoom(dir, "b", {{30, 70}, {70, 20}});
  const std::string c = SaveRoom(dir, "c", {{15, 50}});
  process::CommandResult run = RunFleetmap({"learn-objects", a, b, c, "--out", dir + "/out"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Not a terminal: a line at each stage change (and every 10 s).
  EXPECT_THAT(run.err, HasSubstr("learn-objects: extracting snapshots from 3 maps"));
  EXPECT_THAT(run.err, HasSubstr("learn-objects: searching (N "));
  EXPECT_THAT(run.err, HasSubstr("learn-objects: done: "));
  // A budget far too small: the model is still learned, degraded, and the warnings say so.
  run = RunFleetmap(
      {"learn-objects", a, b, c, "--out", dir + "/small", "--memory-budget", "0.01", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("memory budget"));
  const nlohmann::json model = nlohmann::json::parse(run.out);
  EXPECT_GE(model["num_objects"].get<int>(), 1);
  EXPECT_TRUE(model["degraded"].get<bool>());
  std::filesystem::remove_all(dir);
}

TEST(CliObjectsTest, NothingMovedIsAnEmptyResultNotAnError) {
  const std::string dir = TempDir("empty");
  const std::string a = SaveRoom(dir, "a", {{10, 10}});
  const std::string b = SaveRoom(dir, "b", {{10, 10}});
  const process::CommandResult run = RunFleetmap({"learn-objects", a, b, "--out", dir + "/out"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("No object moved"));
  const nlohmann::json model = nlohmann::json::parse(ReadFile(dir + "/out/model.json"));
  EXPECT_EQ(model["num_objects"].get<int>(), 0);
  std::filesystem::remove_all(dir);
}

TEST(CliObjectsTest, BadInputNamesTheFileAndExitsTwo) {
  const std::string dir = TempDir("bad");
  const std::string a = SaveRoom(dir, "a", {{10, 10}});
  const std::string wide = SaveRoom(dir, "wide", {{10, 10}}, 120);
  process::CommandResult run = RunFleetmap({"learn-objects", a, "--out", dir + "/out"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("at least two maps"));
  run = RunFleetmap({"learn-objects", a, wide, "--out", dir + "/out"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("wide.yaml"));
  EXPECT_THAT(run.err, HasSubstr("a.yaml"));
  EXPECT_THAT(run.err, HasSubstr("size"));
  run = RunFleetmap({"learn-objects", a, dir + "/missing.yaml", "--out", dir + "/out"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("missing.yaml"));
  run = RunFleetmap({"bench", "objects", "--starts", "0"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("--starts"));
  std::filesystem::remove_all(dir);
}

// The flat/hierarchical contrast at a small size: one condition, one data set, two starts; the
// table, the CSV and the JSON agree. On data seed 1 both starts of both models reach the true
// partition and the same optimum (docs/results.md: 19 of 20 each).
TEST(CliObjectsTest, TheContrastBenchmarkReportsGoodStartsOfBothModels) {
  const std::string dir = TempDir("contrast");
  const process::CommandResult run =
      RunFleetmap({"bench", "objects", "--contrast", "--condition", "paper", "--data-sets", "1",
                   "--starts", "2", "--out", dir});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_THAT(run.err, HasSubstr("contrast 1/1: paper"));  // progress
  EXPECT_THAT(run.out, HasSubstr("| paper | none: 2 chairs, a bin, a box"));
  const nlohmann::json json = nlohmann::json::parse(ReadFile(dir + "/contrast.json"));
  ASSERT_EQ(json["conditions"].size(), 1u);
  const nlohmann::json& row = json["conditions"][0];
  EXPECT_EQ(row["condition"], "paper");
  EXPECT_EQ(row["starts"].get<int>(), 2);
  for (const char* model : {"hierarchical", "flat"}) {
    EXPECT_EQ(row[model]["train_log_likelihood"].size(), 2u) << model;
    EXPECT_EQ(row[model]["near_best"].get<int>(), 2) << model;
    EXPECT_EQ(row[model]["good"].get<int>(), 2) << model;
    EXPECT_NE(row[model]["test_log_likelihood"].get<double>(), 0.0) << model;
  }
  EXPECT_THAT(ReadFile(dir + "/contrast.csv"), HasSubstr("\npaper,1,9,"));
  EXPECT_THAT(ReadFile(dir + "/contrast.md"), HasSubstr("| paper |"));
  std::filesystem::remove_all(dir);
}

TEST(CliObjectsTest, AnUnknownContrastConditionIsNamedWithTheKnownOnes) {
  const process::CommandResult run =
      RunFleetmap({"bench", "objects", "--contrast", "--condition", "upside-down"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("unknown condition"));
  EXPECT_THAT(run.err, HasSubstr("'many-of-few'"));
  EXPECT_EQ(RunFleetmap({"bench", "objects", "--contrast", "--data-sets", "0"}).exit_code, 2);
}

// An output that cannot be written is an error naming the file (it used to be ignored, exit 0).
// model.json is a non-empty directory, so the rename over it fails even for root.
TEST(CliObjectsTest, UnwritableOutputNamesTheFileAndExitsTwo) {
  const std::string dir = TempDir("unwritable");
  const std::string a = SaveRoom(dir, "a", {{10, 10}, {60, 60}});
  const std::string b = SaveRoom(dir, "b", {{30, 70}, {70, 20}});
  std::filesystem::create_directories(dir + "/out/model.json/keep");
  const process::CommandResult run = RunFleetmap({"learn-objects", a, b, "--out", dir + "/out"});
  EXPECT_EQ(run.exit_code, 2) << run.out << run.err;
  EXPECT_THAT(run.err, HasSubstr(dir + "/out/model.json: cannot write: Is a directory"));
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/out/model.json/keep"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fleetmap::cli
