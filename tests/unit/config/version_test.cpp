#include "common/config/version.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "common/process/subprocess.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::config {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::StartsWith;

TEST(VersionTest, NamesTheVersionTheCommitAndFastDds) {
  EXPECT_EQ(FleetmapVersion(), FLEETMAP_PROJECT_VERSION);
  EXPECT_THAT(std::string(GitCommit()), MatchesRegex("[0-9a-f]{12}(-dirty)?|unknown"));
  EXPECT_THAT(std::string(FastDdsVersion()), MatchesRegex("2\\.[0-9]+\\.[0-9]+"));
  const std::string text = VersionText("fleetmap-server");
  EXPECT_THAT(text, StartsWith("fleetmap-server " FLEETMAP_PROJECT_VERSION " (commit "));
  EXPECT_THAT(text, HasSubstr("\nFast DDS " + std::string(FastDdsVersion())));
}

// The build-time script on a source tree without .git (a release tarball): the commit is
// "unknown", and the build does not fail.
TEST(VersionTest, ASourceTreeWithoutGitHasAnUnknownCommit) {
  const testing::ScratchDir dir("version_tarball");
  {
    std::ofstream(dir.Path("template.in"))
        << "version @FLEETMAP_VERSION@ commit @FLEETMAP_GIT_COMMIT@\n";
  }
  const process::CommandResult run = process::RunCommand(
      {FLEETMAP_CMAKE_COMMAND, "-DSOURCE_DIR=" + dir.Path(""), "-DFLEETMAP_VERSION=1.2.3",
       "-DTEMPLATE=" + dir.Path("template.in"), "-DOUTPUT=" + dir.Path("out.hpp"), "-P",
       std::string(FLEETMAP_SOURCE_DIR) + "/cmake/FleetmapBuildVersion.cmake"});
  ASSERT_EQ(run.exit_code, 0) << run.output();
  EXPECT_EQ(testing::ReadFile(dir.Path("out.hpp")), "version 1.2.3 commit unknown\n");
}

}  // namespace
}  // namespace fleetmap::config
