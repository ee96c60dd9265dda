#include "tests/docs/synopsis_check.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "tests/scratch_dir.hpp"

namespace fleetmap::docs {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::UnorderedElementsAre;

// CLI11's help, as fleetmap's programs print it.
constexpr char kToolHelp[] = R"(tool: a map tool
Usage: ./tool [OPTIONS] SUBCOMMAND

Options:
  -h,--help                   Print this help message and exit
  --version                   Print the version

Subcommands:
  info                        Print a map's size
  bench                       Benchmark drivers


Footer:
  tool info --not-an-option   prose, not an option
)";

constexpr char kInfoHelp[] = R"(Print a map's size
Usage: ./tool info [OPTIONS] map

Positionals:
  map TEXT REQUIRED           the map

Options:
  -h,--help                   Print this help message and exit
  --json                      JSON output
  --no-compare{false}         a flag with its default
  -o,--out TEXT               where to write
  --duration FLOAT:NONNEGATIVE
                              seconds to run (0: until Ctrl-C)
)";

constexpr char kBenchHelp[] = R"(Benchmark drivers
Usage: ./tool bench [OPTIONS] SUBCOMMAND

Options:
  -h,--help                   Print this help message and exit

Subcommands:
  fleet                       Fleets
  loss                        Lossy UDP
)";

constexpr char kFleetHelp[] = R"(Fleets
Options:
  -h,--help                   Print this help message and exit
  --robots INT ...            fleet sizes
  --out TEXT                  where to write
)";

TEST(ParseHelpTest, ReadsOptionsAndSubcommands) {
  const HelpText tool = ParseHelp(kToolHelp);
  EXPECT_THAT(tool.options, ElementsAre("-h", "--help", "--version"));
  EXPECT_THAT(tool.subcommands, ElementsAre("info", "bench"));
  const HelpText info = ParseHelp(kInfoHelp);
  EXPECT_THAT(info.options,
              ElementsAre("-h", "--help", "--json", "--no-compare", "-o", "--out", "--duration"));
  EXPECT_THAT(info.subcommands, IsEmpty());
}

// A fake `tool` that prints the help above, and `server`, a program without subcommands.
class SynopsisCheckTest : public ::testing::Test {
 protected:
  SynopsisCheckTest() : scratch_("synopsis_check") {
    programs_["tool"] = Script("tool",
                               "case \"$*\" in\n"
                               "  --help) cat <<'EOF'\n" +
                                   std::string(kToolHelp) +
                                   "EOF\n;;\n"
                                   "  'info --help') cat <<'EOF'\n" +
                                   kInfoHelp +
                                   "EOF\n;;\n"
                                   "  'bench --help') cat <<'EOF'\n" +
                                   kBenchHelp +
                                   "EOF\n;;\n"
                                   "  'bench fleet --help'|'bench loss --help') cat <<'EOF'\n" +
                                   kFleetHelp + "EOF\n;;\n  *) exit 109;;\nesac\n");
    programs_["tool-server"] = Script("tool-server", "echo 'Options:'; echo '  --store TEXT'\n");
  }

  std::string Script(const std::string& name, const std::string& body) {
    const std::string path = scratch_.Path(name);
    std::ofstream(path) << "#!/bin/bash\n" << body;
    chmod(path.c_str(), 0755);
    return path;
  }

  std::vector<std::string> Check(std::vector<std::string> lines) {
    DocBlock block;
    block.file = "doc.md";
    block.line = 10;
    block.language = "sh";
    block.mode = BlockMode::kSynopsis;
    block.lines = std::move(lines);
    return CheckSynopsis(block, programs_);
  }

  testing::ScratchDir scratch_;
  std::map<std::string, std::string> programs_;
};

TEST_F(SynopsisCheckTest, ASynopsisThatAgreesPasses) {
  EXPECT_THAT(Check({
                  "tool info MAP [--json] [-o FILE] [--duration=S]   # --nothing in a comment",
                  "tool info | bench ...",
                  "tool bench fleet|loss --robots 1 4 16 [--out DIR]",
                  "tool-server [--store fleet.db]",
                  "            [--store x]   # indented: still tool-server's",
                  "tool-server --store a ; tool info --json",
                  "build/bin/tool info --json \\",
                  "  --out x",
                  "",
              }),
              IsEmpty());
}

TEST_F(SynopsisCheckTest, AnOptionTheProgramLacksIsNamedWithItsLine) {
  EXPECT_THAT(Check({"tool info MAP", "  [--jsn]", "tool-server [--store fleet.db] [--name NAME]"}),
              ElementsAre("doc.md:11: `tool info` has no option --jsn (not in its --help)",
                          "doc.md:13: `tool-server` has no option --name (not in its --help)"));
  // An option must be in each of the alternatives' help; `-1|0|1` is a value, not an option.
  EXPECT_THAT(Check({"tool bench fleet|loss --out X [--level -1|0|1]"}),
              UnorderedElementsAre(HasSubstr("`tool bench fleet` has no option --level"),
                                   HasSubstr("`tool bench loss` has no option --level")));
  // A line after `;` is a command of its own.
  EXPECT_THAT(Check({"tool info --json ; tool-server --json"}),
              ElementsAre(HasSubstr("`tool-server` has no option --json")));
}

// A benchmark's record: the command is checked, its output is not a command.
TEST_F(SynopsisCheckTest, AConsoleBlockChecksOnlyItsCommands) {
  DocBlock block;
  block.file = "doc.md";
  block.line = 10;
  block.language = "console";
  block.lines = {"$ tool bench fleet --robots 8 --out out/x", "", "  --sizes 1 2 3",
                 "$ tool info --jsn"};
  EXPECT_THAT(CheckSynopsis(block, programs_),
              ElementsAre("doc.md:14: `tool info` has no option --jsn (not in its --help)"));
}

TEST_F(SynopsisCheckTest, AMissingSubcommandOrProgramIsNamed) {
  EXPECT_THAT(Check({"tool bench flet --robots 4"}),
              ElementsAre("doc.md:11: `tool bench` has no subcommand flet"));
  EXPECT_THAT(Check({"tool info | validate"}),
              ElementsAre("doc.md:11: `tool` has no subcommand validate"));
  EXPECT_THAT(Check({"make run"}),
              ElementsAre(HasSubstr("doc.md:11: `make` is not a program the test knows")));
}

}  // namespace
}  // namespace fleetmap::docs
