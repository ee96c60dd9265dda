// `fleetmap sim --unknown-poses`: robots that map in their own frames, placed by a real server.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap {
namespace {

using ::testing::HasSubstr;

using testing::RunFleetmap;

TEST(CliSimUnknownPosesTest, EveryRobotIsPlacedNearItsTruePose) {
  const std::string out = ::testing::TempDir() + "/sim_unknown_poses_" + std::to_string(getpid());
  std::filesystem::remove_all(out);
  // A small office mapped quickly: both robots know most of it within seconds, which leaves a
  // loaded machine many registration retries before the run ends.
  const auto result =
      RunFleetmap({"sim", "--unknown-poses", "--robots", "2", "--terrain", "office", "--size", "10",
                   "--seed", "3", "--duration", "20", "--rate", "40", "--out", out});
  ASSERT_EQ(result.exit_code, 0) << result.output();
  EXPECT_THAT(result.out, HasSubstr("Unknown poses: 2 of 2 robots placed"));
  EXPECT_TRUE(std::filesystem::exists(out + "/placement.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/fused.png"));

  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& placements = report["unknown_poses"];
  EXPECT_EQ(placements["robots_placed"], 2);
  // One robot anchored the fleet frame (its last state may read "given": the server notes the
  // placement it already has when the robot's first status comes after its first tiles).
  const std::string anchor = placements["anchor"].get<std::string>();
  EXPECT_TRUE(anchor == "robot0" || anchor == "robot1") << anchor;
  for (const char* robot : {"robot0", "robot1"}) {
    ASSERT_TRUE(placements["per_robot"].contains(robot)) << robot;
    const nlohmann::json& placement = placements["per_robot"][robot];
    EXPECT_TRUE(placement["placed"].get<bool>()) << robot;
    if (robot != anchor) {
      EXPECT_THAT(placement["state"].get<std::string>(), ::testing::AnyOf("placed", "revised"));
    }
    // The frames are far apart and turned (the sim's random transforms), the placement is not.
    ASSERT_FALSE(placement["error_cells"].is_null()) << robot;
    EXPECT_LE(placement["error_cells"].get<double>(), 4.0) << robot;
    EXPECT_LE(placement["yaw_error_deg"].get<double>(), 2.0) << robot;
    EXPECT_GT(placement["known_cells"].get<int64_t>(), 0) << robot;
  }
  // Scored in the terrain's frame: a misplaced or unmoved fused map would not reach this.
  EXPECT_GT(report["quality"]["updf"].get<double>(), 90.0);
  std::filesystem::remove_all(out);
}

TEST(CliSimUnknownPosesTest, CompareKnownNeedsUnknownPoses) {
  const auto result = RunFleetmap({"sim", "--compare-known"});
  EXPECT_NE(result.exit_code, 0);
  EXPECT_THAT(result.output(), HasSubstr("--unknown-poses"));
}

}  // namespace
}  // namespace fleetmap
