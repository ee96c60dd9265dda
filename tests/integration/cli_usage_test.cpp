// Usage errors, --help and --version of every program and every subcommand, run as a user runs
// them (the real binaries of this build): a usage error exits 2 with a message naming the
// command and the option, never CLI11's own codes (105, 106, 109...); --help exits 0; --version
// names the fleetmap version, the git commit and the Fast DDS version.
//
// The table below lists every command; a test reads the commands `--help` lists, so a new
// subcommand without a row fails. What each command needs (its required arguments, a numeric
// option to give a bad value) is read from its own --help.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using ::testing::StartsWith;

// A usage error is found before anything runs; this only bounds a hang.
constexpr std::chrono::seconds kTimeout{30};

const std::string kFleetmapBinary = std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap";

// A program and the subcommand path to one of its commands ({} for the program itself).
struct Command {
  std::string binary;
  std::vector<std::string> path;
};

std::string Name(const Command& command) {
  std::string name = command.binary.substr(command.binary.rfind('/') + 1);
  for (const std::string& part : command.path) name.append(" ").append(part);
  return name;
}

// Every command of every program: the table the tests run.
std::vector<Command> AllCommands() {
  std::vector<Command> commands = {{testing::kServerBinary, {}}, {testing::kAgentBinary, {}}};
  for (const char* name :
       {"info", "sim", "terrain", "vectorize", "validate", "rasterize", "compare", "render",
        "extrapolate", "learn-objects", "register", "save-map", "view", "admit", "route-graph"}) {
    commands.push_back({kFleetmapBinary, {name}});
  }
  for (const char* name : {"fleet", "loss", "quarantine", "failover", "capacity", "flood", "paper",
                           "vectorize", "extrapolation", "objects", "register", "route-graph"}) {
    commands.push_back({kFleetmapBinary, {"bench", name}});
  }
  for (const char* name : {"init", "enroll", "revoke", "show"}) {
    commands.push_back({kFleetmapBinary, {"security", name}});
  }
  return commands;
}

process::CommandResult RunProgram(const Command& command, const std::vector<std::string>& args) {
  std::vector<std::string> argv = {command.binary};
  argv.insert(argv.end(), command.path.begin(), command.path.end());
  argv.insert(argv.end(), args.begin(), args.end());
  return process::RunCommand(std::move(argv), kTimeout);
}

// One row of a CLI11 help section: "  -o,--output TEXT REQUIRED   what it is".
struct HelpRow {
  std::string name;  // the long name ("--output"), or a positional's or subcommand's name
  std::string type;  // "TEXT", "INT:POSITIVE", "FLOAT ...", or empty for a flag
  bool required = false;
};

// The rows of one section ("Positionals:", "Options:", "Subcommands:") of a --help text.
std::vector<HelpRow> HelpSection(const std::string& help, const std::string& section) {
  std::vector<HelpRow> rows;
  std::istringstream lines(help);
  std::string line;
  bool inside = false;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] != ' ') {
      inside = line == section;
      continue;
    }
    if (!inside || line.size() < 3 || line[2] == ' ') continue;
    // The name column ("-o,--output TEXT REQUIRED") ends where two spaces start the description.
    const size_t end = line.find("  ", 2);
    std::istringstream columns(line.substr(2, end == std::string::npos ? end : end - 2));
    HelpRow row;
    std::string word;
    columns >> word;
    row.name = word.substr(word.rfind(',') + 1);
    if (columns >> word) row.type = word;
    while (columns >> word) row.required = row.required || word == "REQUIRED";
    rows.push_back(row);
  }
  return rows;
}

std::string Help(const Command& command) {
  const process::CommandResult help = RunProgram(command, {"--help"});
  EXPECT_EQ(help.exit_code, 0) << Name(command) << ": " << help.output();
  return help.out;
}

// Arguments that satisfy what the command requires, so that the usage error under test is the
// one reported: "x" for each required positional and option.
std::vector<std::string> RequiredArguments(const std::string& help) {
  std::vector<std::string> args;
  for (const HelpRow& row : HelpSection(help, "Positionals:")) {
    if (row.required) args.push_back("x");
  }
  for (const HelpRow& row : HelpSection(help, "Options:")) {
    if (row.required && row.name.starts_with("--")) {
      args.push_back(row.name);
      args.push_back("x");
    }
  }
  return args;
}

// The first option that takes a number, if the command has one.
std::optional<std::string> NumericOption(const std::string& help) {
  for (const HelpRow& row : HelpSection(help, "Options:")) {
    if (row.name.starts_with("--") &&
        (row.type.starts_with("INT") || row.type.starts_with("UINT") ||
         row.type.starts_with("FLOAT"))) {
      return row.name;
    }
  }
  return std::nullopt;
}

// The table is every command: each program's and subcommand's --help lists no command without a
// row, and the subcommand paths of the table are all there.
TEST(CliUsageTest, TheTableHoldsEveryCommandHelpLists) {
  std::set<std::vector<std::string>> listed;
  std::vector<std::vector<std::string>> to_visit = {{}};
  while (!to_visit.empty()) {
    const std::vector<std::string> path = to_visit.back();
    to_visit.pop_back();
    const std::vector<HelpRow> subcommands =
        HelpSection(Help({kFleetmapBinary, path}), "Subcommands:");
    if (subcommands.empty()) listed.insert(path);
    for (const HelpRow& row : subcommands) {
      std::vector<std::string> sub = path;
      sub.push_back(row.name);
      to_visit.push_back(sub);
    }
  }
  std::set<std::vector<std::string>> in_table;
  for (const Command& command : AllCommands()) {
    if (command.binary == kFleetmapBinary) in_table.insert(command.path);
  }
  EXPECT_EQ(listed, in_table);
}

TEST(CliUsageTest, HelpExitsZeroForEveryCommand) {
  for (const Command& command : AllCommands()) {
    const process::CommandResult help = RunProgram(command, {"--help"});
    EXPECT_EQ(help.exit_code, 0) << Name(command) << ": " << help.output();
    EXPECT_THAT(help.out, HasSubstr("Usage:")) << Name(command);
  }
}

TEST(CliUsageTest, AnUnknownFlagExitsTwoNamingTheCommandAndTheFlag) {
  for (const Command& command : AllCommands()) {
    std::vector<std::string> args = RequiredArguments(Help(command));
    args.push_back("--no-such-flag");
    const process::CommandResult run = RunProgram(command, args);
    EXPECT_EQ(run.exit_code, 2) << Name(command) << ": " << run.output();
    EXPECT_THAT(run.err, HasSubstr("--no-such-flag")) << Name(command);
    EXPECT_THAT(run.err, StartsWith(Name(command) + ": ")) << Name(command);
  }
}

TEST(CliUsageTest, ABadOrMissingNumberExitsTwoNamingTheOption) {
  int checked = 0;
  for (const Command& command : AllCommands()) {
    const std::string help = Help(command);
    const std::optional<std::string> option = NumericOption(help);
    if (!option) continue;
    ++checked;
    std::vector<std::string> args = RequiredArguments(help);
    args.push_back(*option);
    const process::CommandResult missing = RunProgram(command, args);
    EXPECT_EQ(missing.exit_code, 2) << Name(command) << " " << *option << ": " << missing.output();
    EXPECT_THAT(missing.err, HasSubstr(*option)) << Name(command);
    args.push_back("not-a-number");
    const process::CommandResult bad = RunProgram(command, args);
    EXPECT_EQ(bad.exit_code, 2) << Name(command) << " " << *option << ": " << bad.output();
    EXPECT_THAT(bad.err, HasSubstr(*option)) << Name(command);
  }
  // The help parsing found the numeric options (most commands have one).
  EXPECT_GE(checked, 20);
}

TEST(CliUsageTest, MissingRequiredArgumentsAndSubcommandsExitTwo) {
  for (const Command& command :
       {Command{kFleetmapBinary, {}}, Command{kFleetmapBinary, {"bench"}},
        Command{kFleetmapBinary, {"security"}}, Command{kFleetmapBinary, {"info"}},
        Command{kFleetmapBinary, {"register", "a.yaml"}}, Command{testing::kAgentBinary, {}}}) {
    const process::CommandResult run = RunProgram(command, {});
    EXPECT_EQ(run.exit_code, 2) << Name(command) << ": " << run.output();
    EXPECT_THAT(run.err, Not(IsEmpty())) << Name(command);
  }
}

TEST(CliUsageTest, VersionNamesTheVersionTheCommitAndFastDds) {
  for (const std::string& binary :
       {kFleetmapBinary, testing::kServerBinary, testing::kAgentBinary}) {
    const Command program{binary, {}};
    const process::CommandResult run = RunProgram(program, {"--version"});
    EXPECT_EQ(run.exit_code, 0) << run.output();
    EXPECT_THAT(run.out, StartsWith(Name(program) + " " FLEETMAP_PROJECT_VERSION " (commit "));
    EXPECT_THAT(run.out, ::testing::ContainsRegex("commit ([0-9a-f]{12}(-dirty)?|unknown)\\)"));
    EXPECT_THAT(run.out, ::testing::ContainsRegex("Fast DDS 2\\.[0-9]+\\.[0-9]+"));
    EXPECT_THAT(run.err, IsEmpty());
  }
}

}  // namespace
}  // namespace fleetmap
