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
using testing::RunFleetmap;

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

}  // namespace
}  // namespace fleetmap::cli
