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
using ::testing::Not;

using testing::RunFleetmap;

TEST(CliFleetSimTest, SmallFleetReportsBytesLatencyAndQuality) {
  const std::string out = ::testing::TempDir() + "/fleet_sim_" + std::to_string(getpid());
  std::filesystem::remove_all(out);
  const auto result = RunFleetmap({"sim", "--robots", "2", "--terrain", "office", "--size", "10",
                                   "--seed", "3", "--duration", "6", "--rate", "40", "--out", out});
  ASSERT_EQ(result.exit_code, 0) << result.output();
  EXPECT_THAT(result.out, HasSubstr("bytes than the smallest baseline, "));
  // stderr is a pipe here, as in a CI log: each run's progress on lines of its own, no '\r'.
  EXPECT_THAT(result.err, Not(HasSubstr("\r")));
  EXPECT_THAT(result.err, HasSubstr("[tiles wire] 0 / 6 s\n"));
  EXPECT_TRUE(std::filesystem::exists(out + "/report.md"));
  EXPECT_TRUE(std::filesystem::exists(out + "/fused.png"));

  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["robots"], 2);
  ASSERT_TRUE(report["per_robot"].contains("robot0"));
  ASSERT_TRUE(report["per_robot"].contains("robot1"));
  EXPECT_GT(report["tiles_total_bytes"].get<uint64_t>(), 0u);
  // The agents measured every grid wire at their own map changes, to the last patch.
  EXPECT_GT(report["map_changes"].get<uint64_t>(), 0u);
  EXPECT_EQ(report["baselines_pending_patches"].get<uint64_t>(), 0u);
  for (const char* key :
       {"whole_grids", "patches", "patches_zstd3", "patches_zstd19", "patches_lz4"}) {
    EXPECT_GT(report["baselines"][key]["bytes"].get<uint64_t>(), 0u) << key;
  }
  // Patches cost less than whole grids, compressed patches less than raw ones; vector tiles
  // carry the same maps in fewer bytes than whole grids.
  EXPECT_LT(report["baselines"]["patches"]["bytes"].get<uint64_t>(),
            report["baselines"]["whole_grids"]["bytes"].get<uint64_t>());
  EXPECT_LT(report["baselines"]["patches_zstd3"]["bytes"].get<uint64_t>(),
            report["baselines"]["patches"]["bytes"].get<uint64_t>());
  EXPECT_GT(report["baselines"]["whole_grids"]["over_tiles"].get<double>(), 1.0);
  EXPECT_FALSE(report["smallest_baseline"]["key"].get<std::string>().empty());
  // The zstd patch wire ran for real beside it.
  EXPECT_EQ(report["compared_run"]["wire"], "grid-updates-zstd");
  EXPECT_GT(report["compared_run"]["total_bytes"].get<uint64_t>(), 0u);
  EXPECT_GT(report["latency_ms"]["samples"].get<int>(), 0);
  EXPECT_FALSE(report["quality"]["updf"].is_null());
  EXPECT_GT(report["quality"]["updf"].get<double>(), 90.0);
  std::filesystem::remove_all(out);
}

// `fleetmap sim --shards 2` (docs/shards.md): two shard servers and the aggregator, and a
// reference server fusing everything in the same run; the joined map is the reference's.
TEST(CliFleetSimTest, TwoShardsFuseTheMapOneServerFusesInTheSameRun) {
  const std::string out = ::testing::TempDir() + "/fleet_sim_shards_" + std::to_string(getpid());
  std::filesystem::remove_all(out);
  const auto result =
      RunFleetmap({"sim", "--robots", "2", "--terrain", "office", "--size", "30", "--seed", "3",
                   "--duration", "8", "--rate", "40", "--shards", "2", "--out", out});
  ASSERT_EQ(result.exit_code, 0) << result.output();
  EXPECT_THAT(result.out, HasSubstr("2 shards: 0 of "));
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_GT(report["shards"]["cells"].get<int64_t>(), 0);
  EXPECT_EQ(report["shards"]["differing"].get<int64_t>(), 0);
  EXPECT_FALSE(report.contains("compared_run"));  // no grid-wire run with shards
  // Both shards fused tiles: the terrain is cut at 15 m, and the robots map both halves.
  std::ifstream log(out + "/server.log");
  const std::string servers((std::istreambuf_iterator<char>(log)), {});
  EXPECT_THAT(servers, HasSubstr("on rt/fleetmap/shard0/map"));
  EXPECT_THAT(servers, HasSubstr("on rt/fleetmap/shard1/map"));
  EXPECT_THAT(servers, Not(HasSubstr("fused map: 0 tiles")));
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
  const auto shards = RunFleetmap({"sim", "--shards", "9", "--no-compare"});
  EXPECT_EQ(shards.exit_code, 2);
  EXPECT_THAT(shards.err, HasSubstr("--shards must be in 2..8"));
  const auto unknown = RunFleetmap({"sim", "--shards", "2", "--unknown-poses"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("--shards needs known poses"));
  const auto wire = RunFleetmap({"sim", "--compare-wire", "carrier-pigeon"});
  EXPECT_NE(wire.exit_code, 0);
  EXPECT_THAT(wire.output(), HasSubstr("--compare-wire"));
  const auto bench_wire = RunFleetmap({"bench", "fleet", "--compare-wire", "tiles"});
  EXPECT_NE(bench_wire.exit_code, 0);
  EXPECT_THAT(bench_wire.output(), HasSubstr("--compare-wire"));
}

}  // namespace
}  // namespace fleetmap
