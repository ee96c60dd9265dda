#include "common/config/command_line.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/config/version.hpp"

namespace fleetmap::config {
namespace {

using ::testing::HasSubstr;
using ::testing::Optional;

// A program with a checked option and one subcommand, parsed from `args` (after argv[0]).
struct Parsed {
  std::optional<int> exit_code;
  std::string out;
  std::string err;
};

Parsed Parse(std::vector<std::string> args) {
  CLI::App app{"a test program"};
  int count = 1;
  app.add_option("--count", count, "how many")->check(CLI::PositiveNumber);
  CLI::App* show = app.add_subcommand("show", "show something");
  double scale = 1.0;
  show->add_option("--scale", scale, "a scale");
  double offset = 0.0;
  show->add_option("--offset", offset, "an offset")->check(CLI::NonNegativeNumber);
  args.insert(args.begin(), "/usr/bin/testprog");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  Parsed parsed;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  parsed.exit_code = ParseCommandLine(app, static_cast<int>(argv.size()), argv.data());
  parsed.out = ::testing::internal::GetCapturedStdout();
  parsed.err = ::testing::internal::GetCapturedStderr();
  return parsed;
}

TEST(CommandLineTest, AGoodCommandLineGoesOn) {
  EXPECT_EQ(Parse({"--count", "3", "show", "--scale", "0.5"}).exit_code, std::nullopt);
}

TEST(CommandLineTest, HelpAndVersionExitZero) {
  const Parsed help = Parse({"--help"});
  EXPECT_THAT(help.exit_code, Optional(0));
  EXPECT_THAT(help.out, HasSubstr("--count"));
  EXPECT_THAT(help.out, HasSubstr("--version"));
  EXPECT_THAT(Parse({"show", "--help"}).exit_code, Optional(0));
  const Parsed version = Parse({"--version"});
  EXPECT_THAT(version.exit_code, Optional(0));
  EXPECT_THAT(version.out, HasSubstr("testprog " + std::string(FleetmapVersion())));
  EXPECT_THAT(version.out, HasSubstr("Fast DDS"));
}

// CLI11 would exit 109 (unknown flag), 105 (bad value), 106 (failed check); every one is 2, with a
// message that names the command and the option.
TEST(CommandLineTest, EveryRefusedOptionExitsTwoNamingIt) {
  const struct {
    std::vector<std::string> args;
    std::string named;
  } cases[] = {
      {{"--no-such-flag"}, "--no-such-flag"},
      {{"--count", "many"}, "--count"},
      {{"--count", "-4"}, "--count"},
      {{"--count"}, "--count"},
      {{"show", "--scale", "big"}, "--scale"},
      {{"show", "--bogus"}, "--bogus"},
      {{"shw"}, "shw"},
  };
  for (const auto& c : cases) {
    const Parsed parsed = Parse(c.args);
    EXPECT_THAT(parsed.exit_code, Optional(kExitBadCommandLine)) << c.named;
    EXPECT_THAT(parsed.err, HasSubstr(c.named));
    EXPECT_THAT(parsed.err, HasSubstr("testprog"));
  }
  EXPECT_THAT(Parse({"show", "--scale", "big"}).err, HasSubstr("testprog show: "));
  // CLI11's own message would print the largest double in full.
  EXPECT_THAT(Parse({"--count", "-4"}).err, HasSubstr("testprog: --count: must be > 0, got -4"));
  EXPECT_THAT(Parse({"--count", "0"}).err, HasSubstr("must be > 0, got 0"));
  EXPECT_THAT(Parse({"--count", "many"}).err, HasSubstr("'many' is not a number"));
  EXPECT_THAT(Parse({"show", "--offset", "-1"}).err, HasSubstr("--offset: must be >= 0, got -1"));
  EXPECT_EQ(Parse({"show", "--offset", "0"}).exit_code, std::nullopt);
}

}  // namespace
}  // namespace fleetmap::config
