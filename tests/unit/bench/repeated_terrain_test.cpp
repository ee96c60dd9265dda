#include "bench/register/repeated_terrain.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::bench {
namespace {

// Free cells reachable (4-connected) from the terrain's start.
int ReachableFree(const grid::OccupancyGrid& g, const Pose2& start) {
  const int sx = static_cast<int>(start.x / g.resolution());
  const int sy = static_cast<int>(start.y / g.resolution());
  std::vector<uint8_t> seen(static_cast<size_t>(g.cell_count()), 0);
  std::deque<std::pair<int, int>> queue{{sx, sy}};
  seen[static_cast<size_t>(sy) * g.width() + sx] = 1;
  int count = 0;
  while (!queue.empty()) {
    const auto [x, y] = queue.front();
    queue.pop_front();
    ++count;
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nx = x + dx, ny = y + dy;
      if (!g.Contains(nx, ny) || g.StateAt(nx, ny) != grid::CellState::kFree) continue;
      uint8_t& s = seen[static_cast<size_t>(ny) * g.width() + nx];
      if (s == 0) {
        s = 1;
        queue.emplace_back(nx, ny);
      }
    }
  }
  return count;
}

// Every kind makes a terrain a robot can explore (its free space is one piece, reached from the
// start) with structure in it, and a seed gives the same terrain.
TEST(RepeatedTerrainTest, EveryKindIsConnectedFromItsStartAndDeterministic) {
  for (int k = 0; k < kRepeatedKinds; ++k) {
    const auto kind = static_cast<RepeatedKind>(k);
    SCOPED_TRACE(RepeatedKindName(kind));
    for (const uint32_t seed : {1u, 2u, 3u}) {
      const sim::Terrain terrain = RepeatedTerrain(kind, 30.0, seed);
      const StatusOr<grid::OccupancyGrid> g = sim::RasterizeTerrain(terrain, 0.05);
      ASSERT_TRUE(g.ok()) << g.status();
      const grid::StateCounts counts = g->CountStates();
      ASSERT_EQ(g->StateAt(static_cast<int>(terrain.start.x / 0.05),
                           static_cast<int>(terrain.start.y / 0.05)),
                grid::CellState::kFree);
      EXPECT_GT(ReachableFree(*g, terrain.start), 0.95 * counts.free) << "seed " << seed;
      EXPECT_GT(counts.occupied, 0.02 * g->cell_count()) << "seed " << seed;
      const StatusOr<grid::OccupancyGrid> again =
          sim::RasterizeTerrain(RepeatedTerrain(kind, 30.0, seed), 0.05);
      ASSERT_TRUE(again.ok());
      EXPECT_EQ(again->data(), g->data());
    }
  }
}

}  // namespace
}  // namespace fleetmap::bench
