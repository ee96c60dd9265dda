// Runs `fleetmap register` end to end: its JSON line, its text, its exit codes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/inputs/command_inputs.hpp"
#include "common/process/subprocess.hpp"
#include "common/registration/placer.hpp"
#include "common/registration/registration.hpp"
#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap::cli {
namespace {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::RunFleetmap;
using testing::ScratchDir;

std::string DataPath(const std::string& name) {
  return std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/" + name;
}

TEST(CliRegisterTest, PrintsOneJsonLineAndFindsAMapInItself) {
  const std::string map = DataPath("real/aws_small_house.yaml");
  const process::CommandResult run = RunFleetmap({"register", map, map, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out.find('\n'), run.out.size() - 1);
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["found"], true);
  EXPECT_NEAR(json["a_from_b"]["x"].get<double>(), 0.0, 0.15);
  EXPECT_NEAR(json["a_from_b"]["y"].get<double>(), 0.0, 0.15);
  EXPECT_NEAR(json["a_from_b"]["yaw"].get<double>(), 0.0, 0.035);
  EXPECT_GT(json["confidence"].get<double>(), 0.5);
  EXPECT_NEAR(json["overlap"].get<double>(), 1.0, 0.05);
  EXPECT_TRUE(json["ms"].is_number());
}

TEST(CliRegisterTest, PrintsTextAndExplainsConfidence) {
  const std::string map = DataPath("real/strands_kth.yaml");
  const process::CommandResult run = RunFleetmap({"register", map, map});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("found:      yes"));
  EXPECT_THAT(run.out, HasSubstr("confidence: "));
  EXPECT_THAT(run.out, HasSubstr("score: "));
  const process::CommandResult help = RunFleetmap({"register", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("confidence (0..1)"));
}

// "found" is the server's placement decision for the pair: the CLI's default bar is the
// server's, and at any bar the CLI decides as Register does with the server's placement options.
TEST(CliRegisterTest, FoundIsTheServersPlacementDecision) {
  const std::string map = DataPath("real/aws_small_house.yaml");
  const StatusOr<grid::LoadedMap> loaded = LoadGridInput(map, kDefaultMaxCells);
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  registration::PlacementOptions server;

  // A clear pair (the map on itself): placed by both at the default bar.
  process::CommandResult run = RunFleetmap({"register", map, map, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["min_confidence"].get<double>(), server.registration.min_confidence);
  StatusOr<registration::Registration> placed =
      registration::Register(loaded->grid, loaded->grid, server.registration);
  ASSERT_TRUE(placed.ok()) << placed.status();
  EXPECT_TRUE(placed->found) << placed->why_not;
  EXPECT_EQ(json["found"].get<bool>(), placed->found);

  // The same pair under a bar above its confidence (where the CLI used to say found: the pair
  // passes every other check): refused by both, for that reason, the best guess still printed.
  const double confidence = json["confidence"].get<double>();
  ASSERT_LT(confidence, 1.0);
  server.registration.min_confidence = (confidence + 1.0) / 2.0;
  const std::string bar = nlohmann::json(server.registration.min_confidence).dump();
  run = RunFleetmap({"register", map, map, "--json", "--min-confidence", bar});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  json = nlohmann::json::parse(run.out);
  placed = registration::Register(loaded->grid, loaded->grid, server.registration);
  ASSERT_TRUE(placed.ok()) << placed.status();
  EXPECT_FALSE(placed->found);
  EXPECT_EQ(json["found"].get<bool>(), placed->found);
  EXPECT_THAT(placed->why_not, HasSubstr("below the placement bar"));
  EXPECT_THAT(json["why_not"].get<std::string>(), HasSubstr("below the placement bar"));
  EXPECT_FALSE(json.contains("a_from_b"));  // a refused placement is a hint only
  EXPECT_NEAR(json["best_guess"]["x"].get<double>(), 0.0, 0.15);
  EXPECT_NEAR(json["best_guess"]["y"].get<double>(), 0.0, 0.15);
  EXPECT_NEAR(json["best_guess"]["yaw"].get<double>(), 0.0, 0.035);

  run = RunFleetmap({"register", map, map, "--min-confidence", bar});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("found:      no"));
  EXPECT_THAT(run.out, HasSubstr("why not:    confidence "));
  EXPECT_THAT(run.out, HasSubstr("best guess: x "));
}

TEST(CliRegisterTest, RefusesABadMinConfidenceWithExitTwo) {
  const std::string map = DataPath("real/strands_kth.yaml");
  for (const char* bad : {"1.5", "-0.1", "nan", "high", ""}) {
    SCOPED_TRACE(bad);
    const process::CommandResult run = RunFleetmap({"register", map, map, "--min-confidence", bad});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_THAT(run.err, HasSubstr("--min-confidence"));
    EXPECT_EQ(run.out, "");
  }
}

// The drift-tolerant verification (docs/registration.md, Drift): on by default, where a map on
// itself needs no block to move by more than a cell; 0 verifies rigidly, and a bound outside
// [0, 0.2] is a usage error.
TEST(CliRegisterTest, TakesTheDriftBoundAndReportsTheLargestShift) {
  const std::string map = DataPath("real/aws_small_house.yaml");
  process::CommandResult run =
      RunFleetmap({"register", map, map, "--json", "--max-drift-per-m", "0"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["drift_m"], 0.0);
  run = RunFleetmap({"register", map, map, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["found"], true);
  EXPECT_LE(json["drift_m"].get<double>(), 0.05 + 1e-9);  // at most a cell on itself
  for (const char* bad : {"0.5", "-0.01", "x"}) {
    SCOPED_TRACE(bad);
    run = RunFleetmap({"register", map, map, "--max-drift-per-m", bad});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_THAT(run.err, HasSubstr("--max-drift-per-m"));
  }
}

TEST(CliRegisterTest, BadInputExitsTwoNamingTheFile) {
  const std::string map = DataPath("real/strands_kth.yaml");
  process::CommandResult run = RunFleetmap({"register", map, DataPath("missing_image.yaml")});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("missing_image.yaml"));
  run = RunFleetmap({"register", map, DataPath("trinary_4x3.yaml"), "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("trinary_4x3.yaml"));
  EXPECT_THAT(run.err, HasSubstr("resolution"));
}

// Rows per group of pairs (the maps, one repeated-structure terrain, each plain and drifted) and
// overlap, then one for every pair.
TEST(CliRegisterTest, BenchPrintsARowPerGroupAndOverlapAndWritesJsonAndCsv) {
  const ScratchDir dir("cli_bench_register");
  const process::CommandResult run = RunFleetmap(
      {"bench", "register", "--maps", DataPath("real"), "--repeated", "1", "--pairs-per-overlap",
       "1", "--json", dir.Path("r.json"), "--csv", dir.Path("r.csv")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* row :
       {"| maps | 20 % |", "| maps | 70 % |", "| maps drifted | 35 % |", "| repeated | 50 % |",
        "| repeated drifted | all |", "| every pair | all |"}) {
    EXPECT_THAT(run.out, HasSubstr(row));
  }
  EXPECT_THAT(run.out, HasSubstr("m-explore success %"));
  EXPECT_THAT(run.out, HasSubstr("placement bar 0.95"));
  EXPECT_THAT(run.out, HasSubstr("Reliability of fleetmap's confidence"));
  EXPECT_THAT(run.err, HasSubstr("pairs, "));  // progress
  const nlohmann::json json = nlohmann::json::parse(ReadFile(dir.Path("r.json")));
  EXPECT_EQ(json["min_confidence"].get<double>(), 0.95);
  const nlohmann::json& summary = json["summary"];
  ASSERT_EQ(summary.size(), 21u);  // 4 groups x (4 overlaps + all) + every pair
  EXPECT_EQ(summary[0]["group"], "maps");
  EXPECT_EQ(summary[0]["overlap"], "20 %");
  EXPECT_EQ(summary[4]["overlap"], "all");
  EXPECT_EQ(summary[5]["group"], "maps drifted");
  EXPECT_EQ(summary[10]["group"], "repeated");
  EXPECT_EQ(summary[20]["group"], "");
  // Every generated pair is registered plain and drifted.
  EXPECT_EQ(summary[4]["fleetmap"]["pairs"], summary[9]["fleetmap"]["pairs"]);
  EXPECT_EQ(summary[14]["fleetmap"]["pairs"], summary[19]["fleetmap"]["pairs"]);
  EXPECT_EQ(summary[4]["fleetmap"]["pairs"].get<int>() +
                summary[14]["fleetmap"]["pairs"].get<int>() + json["not_generated"].get<int>(),
            16);  // (3 maps + 1 terrain) x 4 overlaps x 1
  EXPECT_EQ(json["reliability"].size(), 6u);
  EXPECT_THAT(ReadFile(dir.Path("r.csv")), HasSubstr("map,group,target_overlap,overlap,method"));
}

TEST(CliRegisterTest, BenchRefusesAMissingMapsDirectory) {
  const process::CommandResult run =
      RunFleetmap({"bench", "register", "--maps", DataPath("no_such_dir")});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("no_such_dir"));
}

}  // namespace
}  // namespace fleetmap::cli
