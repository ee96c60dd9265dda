// `fleetmap bench flood` against a real server and agent: it floods, stops on SIGINT and says what
// it wrote; the server refuses what is over its budgets, keeps the honest robot and exits cleanly.
// Bad options exit 2, as every command's.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <map>
#include <string>
#include <thread>

#include "bench/fleet/bench_flood_command.hpp"
#include "common/process/subprocess.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap {
namespace {

using process::Subprocess;
using std::chrono::seconds;
constexpr seconds kDeadline{30};

const std::string kFleetmap = std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap";

TEST(CliBenchFloodTest, FloodsARunningServerThatRefusesWhatIsOverItsBudgetsAndKeepsServing) {
  const std::map<std::string, std::string> env = {
      {"FLEETMAP_DOMAIN", std::to_string(process::RandomDomainId())},
      {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  Subprocess server(
      {testing::kServerBinary, "--duration", "60", "--no-object-learning", "--no-extrapolation"},
      env);
  ASSERT_TRUE(server.WaitForOutput("listening on DDS domain", kDeadline)) << server.Output();
  Subprocess alpha({testing::kAgentBinary, "--robot-id", "alpha", "--map",
                    std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/trinary_4x3.yaml"},
                   env);
  ASSERT_TRUE(server.WaitForOutput("robot alpha joined", kDeadline)) << server.Output();

  // 2 participants of 40 ids each: more ids than one participant may claim (16 by default).
  Subprocess flood({kFleetmap, "bench", "flood", "--participants", "2", "--ids", "40",
                    "--heavy-tiles", "4", "--keys", "200"},
                   env);
  ASSERT_TRUE(flood.WaitForOutput("flooding rt/fleetmap/robot_tiles", kDeadline)) << flood.Output();
  ASSERT_TRUE(server.WaitForOutput("refused from", kDeadline)) << server.Output();
  std::this_thread::sleep_for(seconds(2));
  flood.Signal(SIGINT);
  ASSERT_EQ(flood.Wait(kDeadline), 0) << flood.Output();
  EXPECT_GT(bench::TilesWrittenByFlood(flood.StdOut()), 0u) << flood.Output();

  alpha.Signal(SIGINT);
  EXPECT_EQ(alpha.Wait(kDeadline), 0) << alpha.Output();
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  EXPECT_NE(server.Output().find("refused: tiles: "), std::string::npos) << server.Output();
}

TEST(CliBenchFloodTest, BadOptionsAreNamedAndExit2) {
  const auto bad_name = testing::RunFleetmap({"bench", "flood", "--robot", "1bad"});
  EXPECT_EQ(bad_name.exit_code, 2);
  EXPECT_NE(bad_name.err.find("--robot \"1bad\""), std::string::npos) << bad_name.output();
  // Refused by the option parser: exit 2 as well, not CLI11's own code.
  const auto out_of_range = testing::RunFleetmap({"bench", "flood", "--participants", "0"});
  EXPECT_EQ(out_of_range.exit_code, 2);
  EXPECT_NE(out_of_range.output().find("--participants"), std::string::npos)
      << out_of_range.output();
}

TEST(CliBenchFloodTest, TheTilesWrittenAreReadFromTheLastReport) {
  EXPECT_EQ(bench::TilesWrittenByFlood("fleetmap bench flood: 2 participant(s) ...\n"
                                       "fleetmap bench flood: 1234 tiles written\n"),
            1234u);
  EXPECT_EQ(bench::TilesWrittenByFlood("fleetmap bench flood: many tiles written\n"), 0u);
  EXPECT_EQ(bench::TilesWrittenByFlood(""), 0u);
}

}  // namespace
}  // namespace fleetmap
