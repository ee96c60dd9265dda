#include "common/core/shard_regions.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap {
namespace {

TEST(ShardRegionTest, ATileIsTheRegionsWhenItsCentreLiesInside) {
  const ShardRegion west{"west", 0.0, 0.0, 30.0, 60.0};
  EXPECT_EQ(west.Tiles(10.0), (TileBox{0, 0, 2, 5}));
  // A border through a tile: the tile goes to the side that holds its centre.
  const ShardRegion left{"left", -7.0, 0.0, 14.0, 10.0};
  EXPECT_EQ(left.Tiles(10.0), (TileBox{-1, 0, 0, 0}));  // centres -5 and 5; 15 is past 14
  const ShardRegion right{"right", 14.0, 0.0, 40.0, 10.0};
  EXPECT_EQ(right.Tiles(10.0), (TileBox{1, 0, 3, 0}));
  EXPECT_TRUE((ShardRegion{"tiny", 1.0, 1.0, 2.0, 2.0}.Tiles(10.0).empty()));
}

TEST(ShardPlanTest, NeighboursOwnDisjointTilesAndATileOnNoRegionHasNoOwner) {
  StatusOr<ShardPlan> plan =
      ShardPlan::Create({ShardRegion{"west", 0, 0, 30, 60}, ShardRegion{"east", 30, 0, 60, 60}});
  ASSERT_TRUE(plan.ok()) << plan.status();
  for (int x = 0; x < 6; ++x) {
    const ShardRegion* owner = plan->OwnerOf(TileId{x, 3}, 10.0);
    ASSERT_NE(owner, nullptr);
    EXPECT_EQ(owner->name, x < 3 ? "west" : "east");
  }
  EXPECT_EQ(plan->OwnerOf(TileId{6, 0}, 10.0), nullptr);
  EXPECT_EQ(plan->OwnerOf(TileId{0, -1}, 10.0), nullptr);
  EXPECT_NE(plan->Find("east"), nullptr);
  EXPECT_EQ(plan->Find("north"), nullptr);
}

TEST(ShardPlanTest, ARobotIsHomedOnItsListedShardElseOnTheFirst) {
  StatusOr<ShardPlan> plan =
      ShardPlan::Create({ShardRegion{"west", 0, 0, 30, 60}, ShardRegion{"east", 30, 0, 60, 60}},
                        {{RobotId{"delta"}, "east"}});
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->HomeOf(RobotId{"delta"}), "east");
  EXPECT_EQ(plan->HomeOf(RobotId{"alpha"}), "west");
  EXPECT_TRUE((ShardAssignment{*plan, "east"}.IsHomeOf(RobotId{"delta"})));
  EXPECT_FALSE((ShardAssignment{*plan, "west"}.IsHomeOf(RobotId{"delta"})));
  StatusOr<ShardPlan> unknown =
      ShardPlan::Create({ShardRegion{"west", 0, 0, 30, 60}}, {{RobotId{"delta"}, "north"}});
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("robot delta is homed on shard north"),
            std::string::npos);
}

TEST(ShardPlanTest, RefusesOverlapsBadNamesTwinsAndRegionsWithoutArea) {
  const auto error = [](std::vector<ShardRegion> regions) {
    StatusOr<ShardPlan> plan = ShardPlan::Create(std::move(regions));
    return plan.ok() ? std::string("ok") : plan.status().message();
  };
  EXPECT_NE(error({{"a", 0, 0, 30, 30}, {"b", 29, 0, 60, 30}}).find("shards a and b overlap"),
            std::string::npos);
  EXPECT_NE(error({{"west/1", 0, 0, 1, 1}}).find("ROS 2 name token"), std::string::npos);
  EXPECT_NE(error({{"a", 0, 0, 1, 1}, {"a", 5, 5, 6, 6}}).find("listed twice"), std::string::npos);
  EXPECT_NE(error({{"a", 5, 0, 5, 1}}).find("has no area"), std::string::npos);
  EXPECT_NE(error({{"a", 0, 0, 1, std::nan("")}}).find("not finite"), std::string::npos);
  EXPECT_NE(error({}).find("at least one shard"), std::string::npos);
  // Sharing a border is not an overlap.
  EXPECT_EQ(error({{"a", 0, 0, 30, 30}, {"b", 30, 0, 60, 30}}), "ok");
}

}  // namespace
}  // namespace fleetmap
