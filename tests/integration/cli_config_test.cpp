// Config files for the three programs an operator deploys (fleetmap-server, fleetmap-agent,
// `fleetmap view`), run as a user runs them: a plain YAML of the long options, a ROS 2 params file
// with a section per node, the order default < file < environment < command line as
// --print-config reports it, its output read back, unknown keys refused with the file and line,
// and a server that really runs on what its file says.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;

constexpr std::chrono::seconds kTimeout{60};
const std::string kFleetmapBinary = std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap";

// A program as the command that starts it.
struct Program {
  std::vector<std::string> command;
  std::string required;  // a setting the program needs, as a line of its config file
};

const std::vector<Program>& Programs() {
  static const std::vector<Program> programs = {
      {{testing::kServerBinary}, ""},
      {{testing::kAgentBinary}, "robot_id: alpha\n"},
      {{kFleetmapBinary, "view"}, ""},
  };
  return programs;
}

process::CommandResult RunProgram(const Program& program, const std::vector<std::string>& args) {
  std::vector<std::string> argv = program.command;
  argv.insert(argv.end(), args.begin(), args.end());
  return process::RunCommand(std::move(argv), kTimeout);
}

// The line of --print-config's output that sets `key`, without its alignment.
std::string PrintedLine(const std::string& printed, const std::string& key) {
  std::istringstream lines(printed);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind(key + ":", 0) == 0 || line.rfind("# " + key + ":", 0) == 0) {
      std::string squeezed;
      for (char c : line) {
        if (c != ' ' || squeezed.empty() || squeezed.back() != ' ') squeezed += c;
      }
      return squeezed;
    }
  }
  return "(no line for " + key + ")";
}

class CliConfigTest : public ::testing::Test {
 protected:
  void SetUp() override { unsetenv("FLEETMAP_DOMAIN"); }
  void TearDown() override { unsetenv("FLEETMAP_DOMAIN"); }

  std::string Write(const std::string& name, const std::string& text) {
    const std::string path = scratch_.Path(name);
    std::ofstream(path) << text;
    return path;
  }

  testing::ScratchDir scratch_{"cli_config"};
};

TEST_F(CliConfigTest, EachProgramTakesItsSettingsFromDefaultFileEnvironmentAndCommandLine) {
  for (const Program& program : Programs()) {
    SCOPED_TRACE(program.command.back());
    const std::string file =
        Write("settings.yaml", program.required + "domain: 11\nlocalhost_only: true\n");
    setenv("FLEETMAP_DOMAIN", "12", 1);
    const auto printed =
        RunProgram(program, {"--config", file, "--duration", "3", "--print-config"});
    unsetenv("FLEETMAP_DOMAIN");
    ASSERT_EQ(printed.exit_code, 0) << printed.output();
    EXPECT_EQ(PrintedLine(printed.out, "domain"), "domain: 12 # environment FLEETMAP_DOMAIN");
    EXPECT_THAT(PrintedLine(printed.out, "localhost-only"),
                MatchesRegex("localhost-only: true # file .*settings.yaml:[0-9]+"));
    EXPECT_EQ(PrintedLine(printed.out, "duration"), "duration: 3 # command line");
    EXPECT_THAT(PrintedLine(printed.out, "discovery-server"), HasSubstr("# default"));

    // Read back, the printed settings are the same settings, now from that file.
    const std::string again_file = Write("printed.yaml", printed.out);
    const auto again = RunProgram(program, {"--config", again_file, "--print-config"});
    ASSERT_EQ(again.exit_code, 0) << again.output();
    EXPECT_THAT(PrintedLine(again.out, "domain"),
                MatchesRegex("domain: 12 # file .*printed.yaml:.*"));
    EXPECT_THAT(PrintedLine(again.out, "duration"), MatchesRegex("duration: 3 # file .*"));
  }
}

TEST_F(CliConfigTest, OneRosParamsFileConfiguresEveryProgramFromItsOwnSection) {
  const std::string params = Write("fleet_params.yaml",
                                   "/**:\n"
                                   "  ros__parameters:\n"
                                   "    use_sim_time: false\n"
                                   "    domain: 21\n"
                                   "amcl:\n"
                                   "  ros__parameters:\n"
                                   "    alpha1: 0.2\n"
                                   "fleetmap_server:\n"
                                   "  ros__parameters:\n"
                                   "    tile_size: 5.0\n"
                                   "    placement:\n"
                                   "      confidence: 0.9\n"
                                   "/robot1/fleetmap_agent:\n"
                                   "  ros__parameters:\n"
                                   "    robot_id: robot1\n"
                                   "    fleet_from_map: [2.0, -1.5, 0.5]\n"
                                   "fleetmap_view:\n"
                                   "  ros__parameters:\n"
                                   "    port: 9000\n");
  const auto server = RunProgram(Programs()[0], {"--config", params, "--print-config"});
  ASSERT_EQ(server.exit_code, 0) << server.output();
  EXPECT_THAT(PrintedLine(server.out, "tile-size"), HasSubstr("tile-size: 5.0 # file"));
  EXPECT_THAT(PrintedLine(server.out, "placement-confidence"),
              HasSubstr("placement-confidence: 0.9 # file"));
  EXPECT_THAT(PrintedLine(server.out, "domain"), HasSubstr("domain: 21 # file"));

  const auto agent = RunProgram(Programs()[1], {"--config", params, "--print-config"});
  ASSERT_EQ(agent.exit_code, 0) << agent.output();
  EXPECT_THAT(PrintedLine(agent.out, "robot-id"), HasSubstr("robot-id: robot1 # file"));
  EXPECT_THAT(PrintedLine(agent.out, "fleet-from-map"),
              HasSubstr("fleet-from-map: [2.0, -1.5, 0.5] # file"));

  const auto view = RunProgram(Programs()[2], {"--config", params, "--print-config"});
  ASSERT_EQ(view.exit_code, 0) << view.output();
  EXPECT_THAT(PrintedLine(view.out, "port"), HasSubstr("port: 9000 # file"));
  EXPECT_THAT(PrintedLine(view.out, "domain"), HasSubstr("domain: 21 # file"));
}

TEST_F(CliConfigTest, UnknownKeysAndBadValuesExitTwoNamingTheFileAndLine) {
  for (const Program& program : Programs()) {
    SCOPED_TRACE(program.command.back());
    const std::string unknown = Write("unknown.yaml", program.required + "\nno_such_option: 1\n");
    const auto refused = RunProgram(program, {"--config", unknown});
    EXPECT_EQ(refused.exit_code, 2) << refused.output();
    EXPECT_THAT(refused.err,
                HasSubstr("unknown.yaml:" + std::to_string(program.required.empty() ? 2 : 3) +
                          ": unknown key no-such-option"));

    const std::string bad = Write("bad.yaml", program.required + "duration: -1\n");
    const auto bad_value = RunProgram(program, {"--config", bad});
    EXPECT_EQ(bad_value.exit_code, 2) << bad_value.output();
    EXPECT_THAT(bad_value.err, HasSubstr("bad.yaml:"));
    EXPECT_THAT(bad_value.err, HasSubstr("--duration: must be >= 0, got -1"));
  }
}

// The examples of docs/config, which `make run` and the Debian package use, are what the
// programs take.
TEST_F(CliConfigTest, TheExampleConfigsOfTheDocsAreTaken) {
  const std::string examples = std::string(FLEETMAP_SOURCE_DIR) + "/docs/config/";
  const std::vector<std::pair<size_t, std::string>> runs = {
      {0, "server.yaml"},       {1, "agent.yaml"},        {2, "view.yaml"},
      {0, "fleet_params.yaml"}, {1, "fleet_params.yaml"}, {2, "fleet_params.yaml"}};
  for (const auto& [index, file] : runs) {
    const Program& program = Programs()[index];
    SCOPED_TRACE(program.command.back() + " " + file);
    std::vector<std::string> args = {"--config", examples + file, "--print-config"};
    if (index == 1) args.insert(args.end(), {"--robot-id", "robot1"});
    const auto printed = RunProgram(program, args);
    ASSERT_EQ(printed.exit_code, 0) << printed.output();
    EXPECT_THAT(printed.out, HasSubstr("# file " + examples + file));
  }
}

// The server runs on what its file says (the store it opens) and its start-up dump shows the
// effective values, the domain from the environment included, not "none".
TEST_F(CliConfigTest, ServerRunsOnItsFileAndItsStartUpDumpShowsEffectiveValues) {
  const int domain = process::RandomDomainId();
  const std::string store = scratch_.Path("fleet.db");
  const std::string file = Write("server.yaml", "store: " + store +
                                                    "\nduration: 1\nlocalhost-only: true\n"
                                                    "no_object_learning: true\n");
  setenv("FLEETMAP_DOMAIN", std::to_string(domain).c_str(), 1);
  const auto run = RunProgram(Programs()[0], {"--config", file});
  ASSERT_EQ(run.exit_code, 0) << run.output();
  EXPECT_TRUE(std::filesystem::exists(store)) << run.output();
  EXPECT_THAT(run.output(), HasSubstr("domain_id: " + std::to_string(domain)));
  EXPECT_THAT(run.output(), HasSubstr("localhost_only: true"));
  EXPECT_THAT(run.output(), HasSubstr("store_path: " + store));
  EXPECT_THAT(run.output(), Not(HasSubstr("domain_id: none")));
}

}  // namespace
}  // namespace fleetmap
