#include "common/config/fleet_transforms.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace fleetmap::config {
namespace {

using ::testing::HasSubstr;

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path =
      ::testing::TempDir() + "/transforms_" + std::to_string(getpid()) + "_" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(FleetTransformsTest, ReadsEveryRobot) {
  const auto transforms = LoadFleetTransforms(
      WriteFile("good", "robots:\n  alpha: [0, 0, 0]\n  beta: [40.5, -2, 1.5707963]\n"));
  ASSERT_TRUE(transforms.ok()) << transforms.status();
  ASSERT_EQ(transforms->size(), 2u);
  EXPECT_EQ(transforms->at(RobotId{"beta"}), (Pose2{40.5, -2.0, 1.5707963}));
}

TEST(FleetTransformsTest, BadFilesNameTheFileAndTheEntry) {
  EXPECT_EQ(LoadFleetTransforms("/nonexistent/t.yaml").status().code(), StatusCode::kNotFound);
  const std::string syntax = WriteFile("syntax", "robots: [unclosed\n");
  EXPECT_THAT(LoadFleetTransforms(syntax).status().message(), HasSubstr(syntax));
  EXPECT_THAT(LoadFleetTransforms(WriteFile("nomap", "cars: {}\n")).status().message(),
              HasSubstr("`robots` map"));
  EXPECT_THAT(
      LoadFleetTransforms(WriteFile("name", "robots:\n  bad/name: [0, 0, 0]\n")).status().message(),
      HasSubstr("bad/name"));
  EXPECT_THAT(
      LoadFleetTransforms(WriteFile("short", "robots:\n  alpha: [0, 0]\n")).status().message(),
      HasSubstr("robots.alpha must be [x, y, yaw]"));
  EXPECT_THAT(LoadFleetTransforms(WriteFile("text", "robots:\n  alpha: [0, north, 0]\n"))
                  .status()
                  .message(),
              HasSubstr("robots.alpha[1] is not a number"));
  EXPECT_THAT(
      LoadFleetTransforms(WriteFile("nan", "robots:\n  alpha: [0, .nan, 0]\n")).status().message(),
      HasSubstr("not finite"));
}

}  // namespace
}  // namespace fleetmap::config
