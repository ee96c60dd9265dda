#include "common/config/configurable_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/config/command_line.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::config {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::Optional;

// The variables the test program reads from the environment; unset around every test.
constexpr const char* kLevelVariable = "FLEETMAP_CONFIG_TEST_LEVEL";
constexpr const char* kQuietVariable = "FLEETMAP_CONFIG_TEST_QUIET";

// A program like the house's: a checked number, a string, a flag, an option of three values, a
// required option, two options that exclude each other, and a subcommand that is configurable.
struct Program {
  double level = 1.0;
  std::string store;
  bool quiet = false;
  std::vector<double> pose = {0.0, 0.0, 0.0};
  std::string robot;
  bool unplaced = false;
  int port = 8080;

  std::optional<int> exit_code;
  std::string out;
  std::string err;
  std::string printed;  // --print-config of the program, if asked
};

Program RunProgram(std::vector<std::string> args) {
  Program program;
  CLI::App app{"a configurable test program"};
  app.add_option("--level", program.level, "a level")->check(CLI::PositiveNumber);
  app.add_option("--store", program.store, "a file");
  app.add_flag("--quiet", program.quiet, "say less");
  auto* pose = app.add_option("--pose", program.pose, "x y yaw")->expected(3);
  app.add_option("--robot", program.robot, "a name")->required();
  app.add_flag("--unplaced", program.unplaced, "no pose")->excludes(pose);
  ConfigurableCommand config(&app, "testprog", "test_node",
                             {{"--level", {kLevelVariable}}, {"--quiet", {kQuietVariable}}});
  args.insert(args.begin(), "/usr/bin/testprog");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  program.exit_code = ParseCommandLine(app, static_cast<int>(argv.size()), argv.data(), {&config});
  if (!program.exit_code && config.print_requested()) {
    std::ostringstream printed;
    config.Print(printed);
    program.printed = printed.str();
  }
  program.out = ::testing::internal::GetCapturedStdout();
  program.err = ::testing::internal::GetCapturedStderr();
  return program;
}

class ConfigurableCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    unsetenv(kLevelVariable);
    unsetenv(kQuietVariable);
  }
  void TearDown() override { SetUp(); }

  std::string Write(const std::string& name, const std::string& text) {
    const std::string path = scratch_.Path(name);
    std::ofstream(path) << text;
    return path;
  }

  testing::ScratchDir scratch_{"configurable_command"};
};

TEST_F(ConfigurableCommandTest, ASettingComesFromDefaultThenFileThenEnvironmentThenCommandLine) {
  const std::string file = Write("p.yaml", "robot: alpha\nlevel: 2\n");
  EXPECT_EQ(RunProgram({"--robot", "alpha"}).level, 1.0);
  EXPECT_EQ(RunProgram({"--config", file}).level, 2.0);
  setenv(kLevelVariable, "3", 1);
  EXPECT_EQ(RunProgram({"--config", file}).level, 3.0);
  EXPECT_EQ(RunProgram({"--config", file, "--level", "4"}).level, 4.0);
  EXPECT_EQ(RunProgram({"--config=" + file, "--level=4"}).level, 4.0);
}

TEST_F(ConfigurableCommandTest, FileSetsFlagsStringsAndSeveralValuesAndMeetsRequirements) {
  const std::string file = Write("p.yaml",
                                 "robot: alpha\nstore: /var/lib/a.db\nquiet: true\n"
                                 "pose: [1.5, -2, 0.25]\n");
  const Program program = RunProgram({"--config", file});
  ASSERT_EQ(program.exit_code, std::nullopt) << program.err;
  EXPECT_EQ(program.robot, "alpha");  // the required option, from the file
  EXPECT_EQ(program.store, "/var/lib/a.db");
  EXPECT_TRUE(program.quiet);
  EXPECT_THAT(program.pose, ElementsAre(1.5, -2.0, 0.25));
}

TEST_F(ConfigurableCommandTest, EnvironmentFlagIsOnWhenOne) {
  setenv(kQuietVariable, "1", 1);
  EXPECT_TRUE(RunProgram({"--robot", "a"}).quiet);
  setenv(kQuietVariable, "0", 1);
  EXPECT_FALSE(RunProgram({"--robot", "a", "--config", Write("p.yaml", "quiet: true\n")}).quiet);
}

TEST_F(ConfigurableCommandTest, AnOptionOnTheCommandLineDropsTheFileSettingsItExcludes) {
  const Program program =
      RunProgram({"--config", Write("p.yaml", "robot: a\npose: [1, 2, 3]\n"), "--unplaced"});
  ASSERT_EQ(program.exit_code, std::nullopt) << program.err;
  EXPECT_TRUE(program.unplaced);
  EXPECT_THAT(program.pose, ElementsAre(0.0, 0.0, 0.0));
}

TEST_F(ConfigurableCommandTest, UnknownKeysAndBadValuesExitTwoNamingTheFileAndLine) {
  const Program unknown = RunProgram({"--config", Write("p.yaml", "robot: a\nlevle: 2\n")});
  EXPECT_THAT(unknown.exit_code, Optional(kExitBadCommandLine));
  EXPECT_THAT(unknown.err,
              HasSubstr("p.yaml:2: unknown key levle: testprog has no option --levle"));

  const Program negative = RunProgram({"--config", Write("n.yaml", "robot: a\n\nlevel: -3\n")});
  EXPECT_THAT(negative.exit_code, Optional(kExitBadCommandLine));
  EXPECT_THAT(negative.err, HasSubstr("n.yaml:3: --level: must be > 0, got -3"));

  const Program arity = RunProgram({"--config", Write("a.yaml", "robot: a\npose: [1, 2]\n")});
  EXPECT_THAT(arity.exit_code, Optional(kExitBadCommandLine));
  EXPECT_THAT(arity.err, HasSubstr("a.yaml:2: pose takes 3 values, got 2"));

  const Program own = RunProgram({"--config", Write("o.yaml", "robot: a\nconfig: other.yaml\n")});
  EXPECT_THAT(own.exit_code, Optional(kExitBadCommandLine));
  EXPECT_THAT(own.err, HasSubstr("o.yaml:2: config cannot be set in a config file"));

  const Program missing = RunProgram({"--config", scratch_.Path("none.yaml")});
  EXPECT_THAT(missing.exit_code, Optional(kExitBadCommandLine));
  EXPECT_THAT(missing.err, HasSubstr("none.yaml: cannot be read"));

  setenv(kLevelVariable, "high", 1);
  const Program environment = RunProgram({"--robot", "a"});
  EXPECT_THAT(environment.exit_code, Optional(kExitBadCommandLine));
  EXPECT_THAT(environment.err, HasSubstr("environment " + std::string(kLevelVariable)));
}

TEST_F(ConfigurableCommandTest, RequiredOptionsStillRequiredWhenNoLayerGivesThem) {
  const Program program = RunProgram({"--config", Write("p.yaml", "level: 2\n")});
  EXPECT_THAT(program.exit_code, Optional(kExitBadCommandLine));
  EXPECT_THAT(program.err, HasSubstr("--robot is required"));
}

TEST_F(ConfigurableCommandTest, HelpComesFirstWhateverIsWrongWithTheFile) {
  const Program program = RunProgram({"--config", scratch_.Path("none.yaml"), "--help"});
  EXPECT_THAT(program.exit_code, Optional(0));
  EXPECT_THAT(program.out, HasSubstr("--print-config"));
}

TEST_F(ConfigurableCommandTest, PrintConfigNamesEachSourceAndReadsBackToTheSameSettings) {
  setenv(kLevelVariable, "3.5", 1);
  const Program first =
      RunProgram({"--config", Write("p.yaml", "robot: alpha\npose: [1, 2, 0.5]\n"), "--quiet",
                  "--print-config"});
  ASSERT_EQ(first.exit_code, std::nullopt) << first.err;
  EXPECT_THAT(first.printed, HasSubstr("level: 3.5"));
  EXPECT_THAT(first.printed, HasSubstr("# environment " + std::string(kLevelVariable)));
  EXPECT_THAT(first.printed, HasSubstr("robot: alpha"));
  EXPECT_THAT(first.printed, HasSubstr("p.yaml:1"));
  EXPECT_THAT(first.printed, HasSubstr("pose: [1, 2, 0.5]"));
  EXPECT_THAT(first.printed, HasSubstr("quiet: true"));
  EXPECT_THAT(first.printed, HasSubstr("# command line"));
  EXPECT_THAT(first.printed, HasSubstr("# store: \"\""));  // a default, commented out
  EXPECT_THAT(first.printed, Not(HasSubstr("print-config:")));

  unsetenv(kLevelVariable);
  const Program again = RunProgram({"--config", Write("printed.yaml", first.printed)});
  ASSERT_EQ(again.exit_code, std::nullopt) << again.err;
  EXPECT_EQ(again.level, 3.5);
  EXPECT_EQ(again.robot, "alpha");
  EXPECT_TRUE(again.quiet);
  EXPECT_THAT(again.pose, ElementsAre(1.0, 2.0, 0.5));
}

TEST_F(ConfigurableCommandTest, RosParamsFileOfTheNodeConfiguresTheProgram) {
  const std::string file = Write("params.yaml",
                                 "/**:\n  ros__parameters:\n    use_sim_time: true\n"
                                 "test_node:\n  ros__parameters:\n    robot: beta\n    level: 6\n");
  const Program program = RunProgram({"--config", file});
  ASSERT_EQ(program.exit_code, std::nullopt) << program.err;
  EXPECT_EQ(program.robot, "beta");
  EXPECT_EQ(program.level, 6.0);
}

// `fleetmap view --config`: a configurable subcommand takes the file when the command line
// selects it, and not otherwise.
TEST_F(ConfigurableCommandTest, ASubcommandTakesItsFileOnlyWhenSelected) {
  CLI::App app{"a tool"};
  app.require_subcommand(1);
  CLI::App* view = app.add_subcommand("view", "serve");
  int port = 8080;
  view->add_option("--port", port, "a port");
  ConfigurableCommand config(view, "testprog view", "test_view");
  CLI::App* other = app.add_subcommand("other", "something else");
  int other_port = 1;
  other->add_option("--port", other_port, "a port");
  const std::string file = Write("v.yaml", "port: 9000\n");
  std::vector<std::string> args = {"testprog", "view", "--config", file};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  EXPECT_EQ(ParseCommandLine(app, static_cast<int>(argv.size()), argv.data(), {&config}),
            std::nullopt);
  EXPECT_EQ(port, 9000);

  std::vector<std::string> other_args = {"testprog", "other", "--port", "2"};
  argv.clear();
  for (std::string& arg : other_args) argv.push_back(arg.data());
  EXPECT_EQ(ParseCommandLine(app, static_cast<int>(argv.size()), argv.data(), {&config}),
            std::nullopt);
  EXPECT_EQ(other_port, 2);
  EXPECT_EQ(port, 9000);  // not parsed again
}

}  // namespace
}  // namespace fleetmap::config
