#include "common/config/shard_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace fleetmap::config {
namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::string path =
      ::testing::TempDir() + "/shard_file_" + std::to_string(getpid()) + "_" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(ShardFileTest, ReadsTheShardsInTheFilesOrder) {
  StatusOr<ShardPlan> plan = LoadShardPlan(
      Write("good", "shards:\n  west: [0, 0, 30.5, 60]\n  east: [30.5, 0, 61, 60]\n"));
  ASSERT_TRUE(plan.ok()) << plan.status();
  ASSERT_EQ(plan->regions().size(), 2u);
  EXPECT_EQ(plan->regions()[0].name, "west");
  EXPECT_EQ(plan->regions()[0].max_x, 30.5);
  EXPECT_EQ(plan->regions()[1].name, "east");
  EXPECT_EQ(plan->HomeOf(RobotId{"anyone"}), "west");
}

TEST(ShardFileTest, ReadsTheRobotsHomes) {
  StatusOr<ShardPlan> plan = LoadShardPlan(
      Write("homes",
            "shards:\n  west: [0, 0, 30, 60]\n  east: [30, 0, 60, 60]\nrobots:\n  delta: east\n"));
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->HomeOf(RobotId{"delta"}), "east");
  EXPECT_FALSE(
      LoadShardPlan(Write("badhome", "shards:\n  west: [0, 0, 1, 1]\nrobots: [x]\n")).ok());
}

TEST(ShardFileTest, ErrorsNameTheFileAndTheEntry) {
  const auto error = [](const std::string& name, const std::string& text) {
    const std::string path = Write(name, text);
    StatusOr<ShardPlan> plan = LoadShardPlan(path);
    EXPECT_FALSE(plan.ok()) << name;
    if (plan.ok()) return std::string();
    EXPECT_NE(plan.status().message().find(path), std::string::npos) << plan.status();
    return plan.status().message();
  };
  EXPECT_NE(error("syntax", "shards: [").find("not valid YAML"), std::string::npos);
  EXPECT_NE(error("none", "robots: {}\n").find("needs a `shards` map"), std::string::npos);
  EXPECT_NE(error("three", "shards:\n  west: [0, 0, 30]\n").find("shards.west must be"),
            std::string::npos);
  EXPECT_NE(error("word", "shards:\n  west: [0, 0, x, 1]\n").find("shards.west[2] is not a number"),
            std::string::npos);
  EXPECT_NE(error("overlap", "shards:\n  a: [0, 0, 2, 2]\n  b: [1, 1, 3, 3]\n").find("overlap"),
            std::string::npos);
  EXPECT_EQ(LoadShardPlan("/nonexistent/shards.yaml").status().code(), StatusCode::kNotFound);
}

}  // namespace
}  // namespace fleetmap::config
