// `fleetmap bench failover` and `fleetmap bench capacity` at small sizes (issue 32): the drivers
// run real servers and robots, and what they report holds. The full sweeps are benchmarks
// (docs/results.md), not tests.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap {
namespace {

using std::chrono::seconds;

nlohmann::json ReadJson(const std::string& path) {
  return nlohmann::json::parse(testing::ReadFile(path), nullptr, false);
}

TEST(CliBenchStandbyTest, AFailoverLeavesEveryReaderOnTheStandbysLatestTiles) {
  const std::string out = testing::FreshTempDir("bench_failover");
  const auto run =
      testing::RunFleetmap({"bench", "failover", "--robots", "2", "--runs", "1", "--warmup", "4",
                            "--after", "4", "--size", "20", "--out", out},
                           seconds(240));
  ASSERT_EQ(run.exit_code, 0) << run.output();
  EXPECT_NE(run.out.find("reader follows the standby"), std::string::npos) << run.output();
  const nlohmann::json runs = ReadJson(out + "/failover.json");
  ASSERT_TRUE(runs.is_array() && runs.size() == 1) << runs.dump();
  const nlohmann::json& failover = runs[0];
  // The reader took the standby's tiles, map and frames, and holds its last revision of every
  // fused tile: nothing the standby wrote while the reader still followed the dead server is lost.
  EXPECT_FALSE(failover["tiles_ms"].is_null()) << failover.dump();
  EXPECT_FALSE(failover["map_ms"].is_null()) << failover.dump();
  EXPECT_FALSE(failover["frames_ms"].is_null()) << failover.dump();
  EXPECT_GT(failover["reader_tiles"].get<int>(), 0);
  EXPECT_EQ(failover["reader_stale"], 0) << failover.dump();
  // The standby fused what a never-killed server fused.
  EXPECT_GT(failover["store_tiles"].get<int>(), 0);
  EXPECT_EQ(failover["missing_tiles"], 0) << failover.dump();
  EXPECT_EQ(failover["differing_cells"], 0) << failover.dump();
}

TEST(CliBenchStandbyTest, ACapacityStageFusesEveryRobotAndReportsItsLatency) {
  const std::string out = testing::FreshTempDir("bench_capacity");
  // With simple discovery and through a Fast DDS discovery server; one server, then two shards
  // (docs/shards.md: two buildings, one in each shard's strip).
  const auto run = testing::RunFleetmap({"bench",
                                         "capacity",
                                         "--robots",
                                         "16",
                                         "--stage",
                                         "3",
                                         "--settle",
                                         "1",
                                         "--steps",
                                         "6",
                                         "--size",
                                         "20",
                                         "--server-core",
                                         "-1",
                                         "--discovery",
                                         "both",
                                         "--shards",
                                         "1",
                                         "2",
                                         "--out",
                                         out},
                                        seconds(240));
  ASSERT_EQ(run.exit_code, 0) << run.output();
  EXPECT_NE(run.out.find("largest fleet with fusion p99"), std::string::npos) << run.output();
  const nlohmann::json stages = ReadJson(out + "/capacity.json");
  ASSERT_TRUE(stages.is_array() && stages.size() == 4) << stages.dump();
  EXPECT_EQ(stages[0]["discovery"], "simple");
  EXPECT_EQ(stages[2]["discovery"], "server");
  for (const nlohmann::json& stage : stages) {
    if (stage["shards"] == 2) {
      ASSERT_EQ(stage["shard_cores"].size(), 2u) << stage.dump();
      // Each shard fused its own building.
      EXPECT_GT(stage["shard_cores"][0].get<double>(), 0.0) << stage.dump();
      EXPECT_GT(stage["shard_cores"][1].get<double>(), 0.0) << stage.dump();
    } else {
      EXPECT_EQ(stage["shards"], 1);
    }
    EXPECT_EQ(stage["robots"], 16);
    EXPECT_EQ(stage["participants"], 8) << "16 a participant, but 8 robots share a building";
    EXPECT_FALSE(stage["joined_s"].is_null()) << "every robot's tiles were fused: " << stage.dump();
    EXPECT_GT(stage["offered_tiles_per_s"].get<double>(), 0.0);
    EXPECT_GT(stage["fused_tiles_per_s"].get<double>(), 0.0);
    EXPECT_GT(stage["latencies"].get<int>(), 0);
    EXPECT_GE(stage["p99_ms"].get<double>(), stage["p50_ms"].get<double>());
    EXPECT_GT(stage["server_cores"].get<double>(), 0.0);
    EXPECT_GT(stage["server_rss_mb"].get<double>(), 0.0);
  }
}

// How discovery grows: a participant per robot, as agent processes are, through a discovery
// server whose CPU the stage reports.
TEST(CliBenchStandbyTest, ACapacityStageWithAParticipantPerRobotReportsDiscoveryCosts) {
  const std::string out = testing::FreshTempDir("bench_capacity_participants");
  const auto run = testing::RunFleetmap({"bench",
                                         "capacity",
                                         "--robots",
                                         "12",
                                         "--robots-per-participant",
                                         "1",
                                         "--stage",
                                         "2",
                                         "--settle",
                                         "0",
                                         "--steps",
                                         "4",
                                         "--size",
                                         "20",
                                         "--rate",
                                         "0.5",
                                         "--server-core",
                                         "-1",
                                         "--discovery",
                                         "server",
                                         "--out",
                                         out},
                                        seconds(240));
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const nlohmann::json stages = ReadJson(out + "/capacity.json");
  ASSERT_TRUE(stages.is_array() && stages.size() == 1) << stages.dump();
  const nlohmann::json& stage = stages[0];
  EXPECT_EQ(stage["participants"], 12);
  ASSERT_FALSE(stage["joined_s"].is_null()) << stage.dump();
  EXPECT_GT(stage["join_mb"].get<double>(), 0.0);
  EXPECT_GT(stage["participants_cpu_s"].get<double>(), 0.0);
  EXPECT_GT(stage["discovery_server_cpu_s"].get<double>(), 0.0) << stage.dump();
  EXPECT_EQ(testing::RunFleetmap({"bench", "capacity", "--robots-per-participant", "0"}).exit_code,
            2);
}

TEST(CliBenchStandbyTest, BadOptionsExitTwo) {
  EXPECT_EQ(testing::RunFleetmap({"bench", "failover", "--robots", "0"}).exit_code, 2);
  EXPECT_EQ(testing::RunFleetmap({"bench", "failover", "--terrain", "moon"}).exit_code, 2);
  const auto no_map = testing::RunFleetmap({"bench", "capacity", "--map", "/nonexistent.yaml"});
  EXPECT_EQ(no_map.exit_code, 2) << no_map.output();
  EXPECT_NE(no_map.output().find("/nonexistent.yaml"), std::string::npos) << no_map.output();
  EXPECT_EQ(testing::RunFleetmap({"bench", "capacity", "--discovery", "gossip"}).exit_code, 2);
}

}  // namespace
}  // namespace fleetmap
