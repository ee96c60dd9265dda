// Runs the real `fleetmap terrain` and `fleetmap bench paper` and checks outputs and exit codes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using testing::ReadFile;
using testing::RunFleetmap;

std::string TempDir(const std::string& name) {
  return testing::FreshTempDir("fleetmap_cli_sim_" + name);
}

TEST(CliSimTest, TerrainWritesMapAndGeoJsonReproducibly) {
  const std::string dir = TempDir("terrain");
  for (const char* name : {"a", "b"}) {
    const process::CommandResult run =
        RunFleetmap({"terrain", "--kind", "office", "--size", "12", "--seed", "7", "-o",
                     dir + "/" + name + ".yaml", "--geojson", dir + "/" + name + ".geojson"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  EXPECT_EQ(ReadFile(dir + "/a.pgm"), ReadFile(dir + "/b.pgm"));
  EXPECT_EQ(ReadFile(dir + "/a.geojson"), ReadFile(dir + "/b.geojson"));
  EXPECT_THAT(ReadFile(dir + "/a.geojson"), HasSubstr("\"door\""));
  EXPECT_THAT(testing::GeoJsonProblems(nlohmann::json::parse(ReadFile(dir + "/a.geojson"))),
              IsEmpty());
  const process::CommandResult info = RunFleetmap({"info", dir + "/a.yaml"});
  EXPECT_THAT(info.out, HasSubstr("240 x 240 cells"));
  std::filesystem::remove_all(dir);
}

TEST(CliSimTest, BadInputNamesTheOptionAndExitsTwo) {
  const std::string dir = TempDir("bad");
  const std::string out = dir + "/x.yaml";
  struct Case {
    std::vector<std::string> args;
    std::string option;
  };
  const std::vector<Case> cases = {
      {{"terrain", "--kind", "cave", "-o", out}, "--kind"},
      {{"terrain", "--size", "0", "-o", out}, "--size"},
      {{"terrain", "--size", "1000", "-o", out}, "--size"},
      {{"terrain", "--resolution", "0", "-o", out}, "--resolution"},
      {{"terrain", "--resolution", "-0.05", "-o", out}, "--resolution"},
      {{"bench", "paper", "--out", dir, "--kinds", "cave"}, "--kinds"},
      {{"bench", "paper", "--out", dir, "--sizes", "-5"}, "--sizes"},
      {{"bench", "paper", "--out", dir, "--resolution", "0"}, "--resolution"},
      {{"bench", "paper", "--out", dir, "--laser-step", "0"}, "--laser-step"},
      {{"bench", "paper", "--out", dir, "--laser-fov", "0"}, "--laser-fov"},
  };
  for (const Case& c : cases) {
    const process::CommandResult run = RunFleetmap(c.args);
    EXPECT_EQ(run.exit_code, 2) << c.option << ": " << run.output();
    EXPECT_THAT(run.err, HasSubstr(c.option));
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  std::filesystem::remove_all(dir);
}

TEST(CliSimTest, BenchPaperWritesReportCsvAndCharts) {
  const std::string dir = TempDir("paper");
  const process::CommandResult run = RunFleetmap(
      {"bench", "paper", "--out", dir, "--sizes", "10", "--kinds", "office,maze", "--seed", "3"});
  ASSERT_EQ(run.exit_code, 0) << run.output();
  EXPECT_THAT(run.out, HasSubstr("| office 10 m |"));
  EXPECT_THAT(run.err, HasSubstr("2/2"));      // the progress bar
  EXPECT_THAT(run.err, Not(HasSubstr("\r")));  // stderr is a pipe: whole lines
  for (const char* file :
       {"report.md", "results.csv", "sizes.png", "quality_office_10.png", "quality_maze_10.png",
        "maps/office_10_robot.png", "maps/office_10_truth_vector.png", "maps/maze_10_robot.yaml"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
  const std::string csv = ReadFile(dir + "/results.csv");
  EXPECT_THAT(csv, HasSubstr("kind,size_m,seed"));
  EXPECT_THAT(csv, HasSubstr("\noffice,10,3,200,200,"));
  // A 10 m terrain is one 10 m tile already: its obstacles as one tile cost the same bytes.
  std::istringstream lines(csv);
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  auto column = [&](const std::string& name) {
    std::istringstream names(header), values(row);
    std::string field, value;
    while (std::getline(names, field, ',') && std::getline(values, value, ',')) {
      if (field == name) return value;
    }
    return std::string("missing");
  };
  EXPECT_NE(column("V_obst_one_tile"), "missing");
  EXPECT_EQ(column("V_obst_one_tile"), column("V_obst"));
  EXPECT_GT(std::stoi(column("V_obst")), 0);
  EXPECT_THAT(ReadFile(dir + "/report.md"), HasSubstr("P / V obst one tile"));
  // The honest baselines: a 10 m terrain is one fleet tile on both sides, sent alone.
  EXPECT_EQ(column("grid_tiles"), "1");
  EXPECT_EQ(column("vector_tiles"), "1");
  EXPECT_EQ(std::stoi(column("grid_tile_raw")), 200 * 200);
  EXPECT_LT(std::stoi(column("grid_tile_zstd19")), std::stoi(column("grid_tile_patch_cdr")));
  EXPECT_GT(std::stoi(column("vector_tile_bytes")), 0);
  EXPECT_NE(column("vector_over_smallest"), "missing");
  EXPECT_THAT(ReadFile(dir + "/report.md"), HasSubstr("| vector / zstd -19 |"));
  EXPECT_THAT(run.out, HasSubstr("Vector tiles / smallest baseline"));
  // Same seed, same robot map bytes.
  const std::string again = TempDir("paper_again");
  ASSERT_EQ(RunFleetmap({"bench", "paper", "--out", again, "--sizes", "10", "--kinds", "office",
                         "--seed", "3", "--no-progress"})
                .exit_code,
            0);
  EXPECT_EQ(ReadFile(dir + "/maps/office_10_robot.pgm"),
            ReadFile(again + "/maps/office_10_robot.pgm"));
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(again);
}

}  // namespace
}  // namespace fleetmap::cli
