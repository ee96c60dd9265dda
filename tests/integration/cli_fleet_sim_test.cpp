// `fleetmap sim`: a real server and real agent processes over DDS on loopback, end to end.

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

TEST(CliFleetSimTest, SmallFleetReportsBytesLatencyAndQuality) {
  const std::string out = ::testing::TempDir() + "/fleet_sim_" + std::to_string(getpid());
  std::filesystem::remove_all(out);
  const auto result = RunFleetmap({"sim", "--robots", "2", "--terrain", "office", "--size", "10",
                                   "--seed", "3", "--duration", "6", "--rate", "40", "--out", out});
  ASSERT_EQ(result.exit_code, 0) << result.output();
  EXPECT_THAT(result.out, HasSubstr("fewer than the grid wire"));
  EXPECT_TRUE(std::filesystem::exists(out + "/report.md"));
  EXPECT_TRUE(std::filesystem::exists(out + "/fused.png"));

  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["robots"], 2);
  ASSERT_TRUE(report["per_robot"].contains("robot0"));
  ASSERT_TRUE(report["per_robot"].contains("robot1"));
  EXPECT_GT(report["tiles_total_bytes"].get<uint64_t>(), 0u);
  // Vector tiles carry the same robots' maps in fewer bytes than whole grids.
  EXPECT_GT(report["grid_over_tiles"].get<double>(), 1.0);
  EXPECT_GT(report["latency_ms"]["samples"].get<int>(), 0);
  EXPECT_FALSE(report["quality"]["updf"].is_null());
  EXPECT_GT(report["quality"]["updf"].get<double>(), 90.0);
  std::filesystem::remove_all(out);
}

TEST(CliFleetSimTest, BadOptionsExitTwoAndNameTheOption) {
  const auto robots = RunFleetmap({"sim", "--robots", "0", "--no-compare"});
  EXPECT_EQ(robots.exit_code, 2);
  EXPECT_THAT(robots.err, HasSubstr("--robots"));
  const auto terrain = RunFleetmap({"sim", "--terrain", "castle"});
  EXPECT_EQ(terrain.exit_code, 2);
  EXPECT_THAT(terrain.err, HasSubstr("castle"));
  const auto size = RunFleetmap({"sim", "--size", "-4"});
  EXPECT_EQ(size.exit_code, 2);
  EXPECT_THAT(size.err, HasSubstr("--size"));
}

}  // namespace
}  // namespace fleetmap
