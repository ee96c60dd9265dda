// Runs `fleetmap register` end to end: its JSON line, its text, its exit codes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "common/process/subprocess.hpp"
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

TEST(CliRegisterTest, BenchPrintsARowPerOverlapAndWritesJsonAndCsv) {
  const ScratchDir dir("cli_bench_register");
  const process::CommandResult run =
      RunFleetmap({"bench", "register", "--maps", DataPath("real"), "--pairs-per-overlap", "1",
                   "--json", dir.Path("r.json"), "--csv", dir.Path("r.csv")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* row : {"| 20 % |", "| 35 % |", "| 50 % |", "| 70 % |", "| all |"}) {
    EXPECT_THAT(run.out, HasSubstr(row));
  }
  EXPECT_THAT(run.out, HasSubstr("m-explore success %"));
  EXPECT_THAT(run.out, HasSubstr("Reliability of fleetmap's confidence"));
  EXPECT_THAT(run.err, HasSubstr("pairs, "));  // progress
  const nlohmann::json json = nlohmann::json::parse(ReadFile(dir.Path("r.json")));
  ASSERT_EQ(json["summary"].size(), 5u);
  EXPECT_EQ(json["summary"][0]["overlap"], "20 %");
  EXPECT_EQ(json["summary"][4]["overlap"], "all");
  EXPECT_EQ(json["summary"][4]["fleetmap"]["pairs"].get<int>() + json["not_generated"].get<int>(),
            12);  // 3 maps x 4 overlaps x 1
  EXPECT_EQ(json["reliability"].size(), 6u);
  EXPECT_THAT(ReadFile(dir.Path("r.csv")), HasSubstr("map,target_overlap,overlap,method"));
}

TEST(CliRegisterTest, BenchRefusesAMissingMapsDirectory) {
  const process::CommandResult run =
      RunFleetmap({"bench", "register", "--maps", DataPath("no_such_dir")});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("no_such_dir"));
}

}  // namespace
}  // namespace fleetmap::cli
