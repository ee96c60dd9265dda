#include "tests/docs/doc_block.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fleetmap::docs {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

std::vector<DocBlock> Read(const std::string& text) { return ReadDocBlocks("doc.md", text); }

TEST(DocBlockTest, ReadsEachBlockWithItsLanguageLineAndLines) {
  const auto blocks = Read(
      "# Title\n"
      "```sh\n"
      "fleetmap info a.yaml\n"
      "```\n"
      "text\n"
      "```text\n"
      "output\n"
      "```\n");
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].language, "sh");
  EXPECT_EQ(blocks[0].line, 2);
  EXPECT_EQ(blocks[0].Where(), "doc.md:2");
  EXPECT_THAT(blocks[0].lines, ElementsAre("fleetmap info a.yaml"));
  EXPECT_EQ(blocks[0].LineOf(0), 3);
  EXPECT_TRUE(blocks[0].IsCommands());
  EXPECT_EQ(blocks[0].mode, BlockMode::kRun);
  EXPECT_THAT(blocks[0].errors, IsEmpty());
  EXPECT_FALSE(blocks[1].IsCommands());
}

TEST(DocBlockTest, OnlyShellLanguagesAreCommands) {
  for (const std::string language : {"sh", "bash", "shell", "console"}) {
    EXPECT_TRUE(Read("```" + language + "\nls\n```\n")[0].IsCommands()) << language;
  }
  for (const std::string language : {"text", "yaml", "json", "cpp", "include-rules"}) {
    EXPECT_FALSE(Read("```" + language + "\nls\n```\n")[0].IsCommands()) << language;
  }
}

// Neither a reader nor the test can tell a command from its output in a block without one.
TEST(DocBlockTest, ABlockWithoutALanguageIsAnError) {
  const auto blocks = Read("```\nfleetmap info a.yaml\n```\n");
  ASSERT_EQ(blocks.size(), 1u);
  ASSERT_EQ(blocks[0].errors.size(), 1u);
  EXPECT_THAT(blocks[0].errors[0], HasSubstr("without a language"));
}

TEST(DocBlockTest, AnUnclosedBlockIsAnError) {
  const auto blocks = Read("```sh\nls\n");
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_THAT(blocks[0].errors, ElementsAre(HasSubstr("no closing fence")));
}

// A block in a list item is typed without the item's indentation.
TEST(DocBlockTest, IndentedFencesLoseTheirIndentation) {
  const auto blocks = Read("- item\n  ```sh\n  ls \\\n    -l\n  ```\n");
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_THAT(blocks[0].lines, ElementsAre("ls \\", "  -l"));
}

TEST(DocBlockTest, MarkersSetTheModeAndTheReason) {
  const auto blocks = Read(
      "<!-- docs-test: skip \u2014 installs packages -->\n"
      "```sh\nmake run\n```\n"
      "<!-- docs-test: synopsis -->\n"
      "\n"
      "```sh\nfleetmap info MAP\n```\n"
      "<!-- docs-test: long-running 5 - a server -->\n"
      "```sh\nfleetmap-server\n```\n"
      "<!-- docs-test: long-running -->\n"
      "```sh\nfleetmap view\n```\n"
      "```sh\nls\n```\n");
  ASSERT_EQ(blocks.size(), 5u);
  EXPECT_EQ(blocks[0].mode, BlockMode::kSkip);
  EXPECT_EQ(blocks[0].reason, "installs packages");
  EXPECT_EQ(blocks[1].mode, BlockMode::kSynopsis);
  EXPECT_EQ(blocks[2].mode, BlockMode::kLongRunning);
  EXPECT_DOUBLE_EQ(blocks[2].hold_seconds, 5.0);
  EXPECT_EQ(blocks[2].reason, "a server");
  EXPECT_EQ(blocks[3].mode, BlockMode::kLongRunning);
  EXPECT_DOUBLE_EQ(blocks[3].hold_seconds, 3.0);
  EXPECT_EQ(blocks[4].mode, BlockMode::kRun);  // a marker holds for the next block only
  for (const DocBlock& block : blocks) EXPECT_THAT(block.errors, IsEmpty()) << block.Where();
}

TEST(DocBlockTest, BadMarkersAreErrors) {
  EXPECT_THAT(Read("<!-- docs-test: skip -->\n```sh\nmake run\n```\n")[0].errors,
              ElementsAre(HasSubstr("must say why")));
  EXPECT_THAT(Read("<!-- docs-test: skipp - typo -->\n```sh\nls\n```\n")[0].errors,
              ElementsAre(HasSubstr("unknown docs-test marker 'skipp'")));
  EXPECT_THAT(Read("<!-- docs-test: synopsis -->\n```text\nls\n```\n")[0].errors,
              ElementsAre(HasSubstr("not commands")));
  const auto dangling = Read("<!-- docs-test: synopsis -->\nSome prose.\n```sh\nls\n```\n");
  ASSERT_EQ(dangling.size(), 2u);
  EXPECT_EQ(dangling[0].line, 1);
  EXPECT_THAT(dangling[0].errors, ElementsAre(HasSubstr("not followed by a block")));
  EXPECT_EQ(dangling[1].mode, BlockMode::kRun);
  EXPECT_THAT(Read("text\n<!-- docs-test: synopsis -->\n")[0].errors,
              ElementsAre(HasSubstr("not followed by a block")));
}

// The test gives each block its domain; a block that chose one could meet another run.
TEST(DocBlockTest, ABlockThatRunsMustNotPinADomain) {
  EXPECT_THAT(Read("```sh\nfleetmap-server --domain 7\n```\n")[0].errors,
              ElementsAre(HasSubstr("sets its own DDS domain (fleetmap-server --domain 7)")));
  EXPECT_THAT(Read("```sh\nFLEETMAP_DOMAIN=3 fleetmap view\n```\n")[0].errors,
              ElementsAre(HasSubstr("sets its own DDS domain")));
  EXPECT_THAT(
      Read("<!-- docs-test: synopsis -->\n```sh\nfleetmap view [--domain 7]\n```\n")[0].errors,
      IsEmpty());
  EXPECT_THAT(Read("```sh\nfleetmap view [--domain N]\n```\n")[0].errors, IsEmpty());
}

// Tests run as root in CI: a block that would build or install is never run by accident.
TEST(DocBlockTest, ABlockThatRunsMustNotBuildOrInstall) {
  for (const std::string line :
       {"make run", "sudo apt-get install x", "cd x && cmake --build build", "CI=1 make test",
        "bash scripts/install-deps.sh", "ls | ctest", "systemctl enable --now fleetmap-server"}) {
    EXPECT_THAT(Read("```sh\n" + line + "\n```\n")[0].errors,
                ElementsAre(HasSubstr("which builds, installs or changes the machine")))
        << line;
  }
  for (const std::string line : {"fleetmap info make.yaml", "echo cmake  # make run", "ls"}) {
    EXPECT_THAT(Read("```sh\n" + line + "\n```\n")[0].errors, IsEmpty()) << line;
  }
  EXPECT_THAT(Read("<!-- docs-test: skip - builds -->\n```sh\nmake run\n```\n")[0].errors,
              IsEmpty());
}

TEST(DocBlockTest, ConsoleBlocksTypeOnlyTheDollarLines) {
  const auto blocks = Read(
      "```console\n"
      "$ fleetmap info a.yaml\n"
      "size: 4 x 3\n"
      "$ fleetmap render a.yaml \\\n"
      "    -o a.png\n"
      "wrote a.png\n"
      "```\n");
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_THAT(TypedLines(blocks[0]), ElementsAre("fleetmap info a.yaml", "",
                                                 "fleetmap render a.yaml \\", "    -o a.png", ""));
  const std::vector<TypedCommand> commands = TypedCommands(blocks[0]);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[0].line, 2);
  EXPECT_EQ(commands[1].line, 4);
  EXPECT_EQ(commands[1].text, "fleetmap render a.yaml \\\n    -o a.png");
}

TEST(DocBlockTest, CommandsSkipBlankAndCommentLines) {
  const auto blocks = Read("```sh\n# first\n\nls &  # in the background\nfleetmap info\n```\n");
  const std::vector<TypedCommand> commands = TypedCommands(blocks[0]);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[0].line, 4);
  EXPECT_EQ(commands[0].text, "ls &  # in the background");
  EXPECT_EQ(commands[1].line, 5);
}

}  // namespace
}  // namespace fleetmap::docs
