#include "common/sim/frame_resample.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::sim {
namespace {

// A seeded office's ground truth with its right third unknown (a robot that mapped part of it).
grid::OccupancyGrid PartlyMappedOffice() {
  auto generator =
      TerrainGenerator::Create({.kind = TerrainKind::kOffice, .size = 12.0, .seed = 5});
  EXPECT_TRUE(generator.ok()) << generator.status();
  auto truth = RasterizeTerrain(generator->Generate(), 0.05);
  EXPECT_TRUE(truth.ok()) << truth.status();
  for (int y = 0; y < truth->height(); ++y) {
    for (int x = 2 * truth->width() / 3; x < truth->width(); ++x) {
      truth->at(x, y) = grid::kUnknownValue;
    }
  }
  return *truth;
}

// `grid` read back onto `like`'s geometry (same frame).
grid::OccupancyGrid OnGeometryOf(const grid::OccupancyGrid& grid, const Transform2& grid_from_like,
                                 const grid::OccupancyGrid& like) {
  grid::OccupancyGrid out(like.width(), like.height(), like.resolution(), like.origin());
  ResampleRigid(grid, grid_from_like, &out);
  return out;
}

TEST(FrameResampleTest, IdentityKeepsTheGrid) {
  const grid::OccupancyGrid world = PartlyMappedOffice();
  EXPECT_EQ(ResampleIntoFrame(world, Transform2::Identity()), world);
}

TEST(FrameResampleTest, QuarterTurnIsExactBothWays) {
  const grid::OccupancyGrid world = PartlyMappedOffice();
  const Transform2 world_from_map = Pose2{-31.0, 17.5, M_PI / 2}.ToTransform();
  const grid::OccupancyGrid own = ResampleIntoFrame(world, world_from_map.inverse());
  EXPECT_EQ(own.width(), world.height());
  EXPECT_EQ(own.height(), world.width());
  EXPECT_EQ(own.CountStates().occupied, world.CountStates().occupied);
  EXPECT_EQ(OnGeometryOf(own, world_from_map.inverse(), world), world);
}

TEST(FrameResampleTest, RotatedFrameCarriedBackMatchesTheWorldGrid) {
  const grid::OccupancyGrid world = PartlyMappedOffice();
  const Transform2 world_from_map = Pose2{23.4, -37.1, 2.1}.ToTransform();
  const grid::OccupancyGrid own = ResampleIntoFrame(world, world_from_map.inverse());
  // Axis-aligned in the robot's own frame, its corner on the lattice of whole cells.
  EXPECT_EQ(own.origin().yaw, 0.0);
  const double r = own.resolution();
  EXPECT_NEAR(own.origin().x / r, std::round(own.origin().x / r), 1e-9);
  EXPECT_NEAR(own.origin().y / r, std::round(own.origin().y / r), 1e-9);
  // A world point reads the same state through the robot's frame as on the world grid.
  const grid::OccupancyGrid back = OnGeometryOf(own, world_from_map.inverse(), world);
  int64_t known = 0, agree = 0, occupied = 0, occupied_near = 0;
  for (int y = 0; y < world.height(); ++y) {
    for (int x = 0; x < world.width(); ++x) {
      if (world.StateAt(x, y) == grid::CellState::kUnknown) continue;
      ++known;
      agree += back.at(x, y) == world.at(x, y);
      if (world.StateAt(x, y) != grid::CellState::kOccupied) continue;
      ++occupied;
      // Two nearest-neighbour reads move a cell by at most sqrt(2) cells: a wall stays within 2.
      bool found = false;
      for (int dy = -2; dy <= 2 && !found; ++dy) {
        for (int dx = -2; dx <= 2 && !found; ++dx) {
          found = back.Contains(x + dx, y + dy) &&
                  back.StateAt(x + dx, y + dy) == grid::CellState::kOccupied;
        }
      }
      occupied_near += found;
    }
  }
  ASSERT_GT(known, 10000);
  EXPECT_GT(static_cast<double>(agree) / known, 0.95);
  EXPECT_EQ(occupied_near, occupied);
  // The known area is kept: a rotation neither grows nor shrinks it beyond the edge cells.
  const auto world_known = world.CountStates();
  const auto own_known = own.CountStates();
  EXPECT_NEAR(static_cast<double>(own_known.free + own_known.occupied),
              static_cast<double>(world_known.free + world_known.occupied), 0.02 * known);
}

}  // namespace
}  // namespace fleetmap::sim
