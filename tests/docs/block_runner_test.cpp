#include "tests/docs/block_runner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>

#include "tests/scratch_dir.hpp"

namespace fleetmap::docs {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using namespace std::chrono_literals;

// The block of a document that has it at line 10 (its first command at line 11).
DocBlock Block(const std::string& language, std::vector<std::string> lines,
               BlockMode mode = BlockMode::kRun) {
  DocBlock block;
  block.file = "doc.md";
  block.line = 10;
  block.language = language;
  block.mode = mode;
  block.hold_seconds = 0.5;
  block.lines = std::move(lines);
  return block;
}

class BlockRunnerTest : public ::testing::Test {
 protected:
  BlockRunnerTest() : scratch_("block_runner") {
    settings_.directory = scratch_.Path("");
    settings_.environment["FLEETMAP_DOMAIN"] = "42";
    settings_.time_limit = 5s;
    settings_.stop_limit = 2s;
  }

  // Whether the process whose id a block wrote to `file` still runs.
  bool Alive(const std::string& file) const {
    const pid_t pid = std::stoi(testing::ReadFile(scratch_.Path(file)));
    return pid > 0 && kill(pid, 0) == 0;
  }

  testing::ScratchDir scratch_;
  RunSettings settings_;
};

TEST_F(BlockRunnerTest, ABlockThatRunsHasNoFailures) {
  // In the directory, with the settings' environment, one script: state carries across lines.
  const DocBlock block = Block("sh", {"echo hello > out.txt", "name=out.txt", "test -s $name",
                                      "test \"$FLEETMAP_DOMAIN\" = 42", "# a comment", ""});
  EXPECT_THAT(RunBlock(block, settings_), IsEmpty());
  EXPECT_EQ(testing::ReadFile(scratch_.Path("out.txt")), "hello\n");
}

TEST_F(BlockRunnerTest, AFailingCommandIsNamedByItsLineWithItsOutput) {
  const DocBlock block = Block("sh", {"echo first", "ls no-such-file", "echo never"});
  const std::vector<std::string> failures = RunBlock(block, settings_);
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_THAT(failures[0], AllOf(HasSubstr("doc.md:12: exit 2 from `ls no-such-file`"),
                                 HasSubstr("first"), HasSubstr("no-such-file"),
                                 Not(HasSubstr("never")), Not(HasSubstr("fleetmap-docs-test"))));
}

TEST_F(BlockRunnerTest, AFailingPipelineFails) {
  const std::vector<std::string> failures =
      RunBlock(Block("sh", {"false | cat", "echo never"}), settings_);
  EXPECT_THAT(failures, ElementsAre(HasSubstr("doc.md:11: exit 1 from `false | cat`")));
}

TEST_F(BlockRunnerTest, AContinuedCommandIsNamedByItsFirstLine) {
  const DocBlock block = Block("sh", {"true", "ls \\", "  no-such-file"});
  EXPECT_THAT(RunBlock(block, settings_),
              ElementsAre(HasSubstr("doc.md:12: exit 2 from `ls \\\n  no-such-file`")));
}

TEST_F(BlockRunnerTest, ConsoleBlocksRunTheirCommandsNotTheirOutput) {
  const DocBlock ok = Block("console", {"$ echo 1", "no-such-program", "$ true"});
  EXPECT_THAT(RunBlock(ok, settings_), IsEmpty());
  const DocBlock failing = Block("console", {"$ echo 1", "1", "$ ls no-such-file"});
  EXPECT_THAT(RunBlock(failing, settings_),
              ElementsAre(HasSubstr("doc.md:13: exit 2 from `ls no-such-file`")));
}

TEST_F(BlockRunnerTest, ABlockOverItsTimeLimitFails) {
  settings_.time_limit = 300ms;
  EXPECT_THAT(RunBlock(Block("sh", {"sleep 30"}), settings_),
              ElementsAre(HasSubstr("doc.md:10: not done within 0.3 s")));
}

// What a block leaves in the background is stopped when it ends, as a reader's Ctrl-C would.
TEST_F(BlockRunnerTest, WhatABlockLeavesRunningIsStopped) {
  EXPECT_THAT(RunBlock(Block("sh", {"sleep 300 &", "echo $! > pid"}), settings_), IsEmpty());
  EXPECT_FALSE(Alive("pid"));
  // A program that ignores SIGINT and SIGTERM is stopped too, and named.
  settings_.stop_limit = 300ms;
  const DocBlock stubborn =
      Block("sh", {"bash -c \"trap '' INT TERM; touch ready; sleep 300\" &", "echo $! > pid",
                   "while [ ! -e ready ]; do sleep 0.01; done"});
  EXPECT_THAT(RunBlock(stubborn, settings_),
              ElementsAre(HasSubstr("did not stop within 0.3 s of SIGINT, nor of SIGTERM")));
  EXPECT_FALSE(Alive("pid"));
}

// A server that stops cleanly on Ctrl-C: runs until SIGINT, then exits 0.
const std::string kCleanServer =
    "echo $$ > pid-$RANDOM; trap 'exit 0' INT; while true; do sleep 0.05; done";

TEST_F(BlockRunnerTest, LongRunningProgramsRunTogetherAndStopCleanly) {
  const DocBlock block = Block("sh", {kCleanServer, kCleanServer + " &  # the second one", "true"},
                               BlockMode::kLongRunning);
  EXPECT_THAT(RunLongRunning(block, settings_), IsEmpty());
  int pid_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scratch_.Path(""))) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("pid-", 0) != 0) continue;
    ++pid_files;
    EXPECT_FALSE(Alive(name)) << name;
  }
  EXPECT_EQ(pid_files, 2);
}

TEST_F(BlockRunnerTest, ALongRunningProgramThatFailsIsNamed) {
  // The trailing `&` is dropped, so the exit code is seen.
  const DocBlock early =
      Block("sh", {kCleanServer, "echo bad option; exit 3 &"}, BlockMode::kLongRunning);
  EXPECT_THAT(RunLongRunning(early, settings_),
              ElementsAre(AllOf(HasSubstr("doc.md:12: exit 3 from `echo bad option; exit 3 &`"),
                                HasSubstr("bad option"))));
  // Killed by SIGINT rather than stopping: not a clean exit.
  EXPECT_THAT(RunLongRunning(Block("sh", {"sleep 30"}, BlockMode::kLongRunning), settings_),
              ElementsAre(HasSubstr("doc.md:11: exit 130 from `sleep 30` on SIGINT")));
  settings_.stop_limit = 300ms;
  const DocBlock stubborn = Block("sh", {"trap '' INT; sleep 30"}, BlockMode::kLongRunning);
  EXPECT_THAT(RunLongRunning(stubborn, settings_),
              ElementsAre(HasSubstr("did not stop within 0.3 s of SIGINT")));
}

}  // namespace
}  // namespace fleetmap::docs
