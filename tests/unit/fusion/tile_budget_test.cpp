#include "common/fusion/tile_budget.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace fleetmap::fusion {
namespace {

using std::chrono::seconds;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

const auto kSteady = std::chrono::steady_clock::time_point(std::chrono::hours(1));

// A 10 m tile of 5 cm fused cells: 40 000 cells, 480 KB of contributed cells.
fusion::FusionOptions Fusion() { return fusion::FusionOptions(); }

vector_map::VectorMap Square(double side, int holes = 0) {
  vector_map::VectorMap map;
  map.resolution = 0.05;
  map.epsilon = 0.07;
  vector_map::FreePolygon room{{{0, 0}, {side, 0}, {side, side}, {0, side}}, {}};
  for (int i = 0; i < holes; ++i) room.holes.push_back({{1, 1}, {1.1, 1}, {1.1, 1.1}});
  map.free_space.push_back(room);
  return map;
}

// "r" + std::to_string(i) trips GCC 12's -Wrestrict false positive (PR105329) under -O3.
std::string Numbered(const char* prefix, int number) {
  std::string name = prefix;
  name += std::to_string(number);
  return name;
}

TileCost Cost(uint64_t bytes, uint64_t cells = 1000) {
  TileCost cost;
  cost.vertices = 10;
  cost.rings = 1;
  cost.cells = cells;
  cost.bytes = bytes;
  return cost;
}

std::vector<RobotId> Evicted(
    const std::variant<TileBudget::Charged, TileBudget::Refused>& charged) {
  const auto* ok = std::get_if<TileBudget::Charged>(&charged);
  if (ok == nullptr) {
    ADD_FAILURE() << "refused: " << std::get<TileBudget::Refused>(charged).detail;
    return {};
  }
  return ok->evict;
}

TileBudget::Refused RefusalOf(const std::variant<TileBudget::Charged, TileBudget::Refused>& v) {
  const auto* refused = std::get_if<TileBudget::Refused>(&v);
  if (refused == nullptr) {
    ADD_FAILURE() << "charged";
    return {};
  }
  return *refused;
}

TEST(TileCostTest, CountsVerticesRingsPaintedCellsAndTheMemoryHeld) {
  const TileCost cost = CostOf(Square(10.0, 2), Fusion());
  EXPECT_EQ(cost.vertices, 4u + 2 * 3);
  EXPECT_EQ(cost.rings, 3u);
  // The room's 100 m2 in 5 cm cells (the holes' own small areas counted too).
  EXPECT_NEAR(static_cast<double>(cost.cells), 40'000.0, 20.0);
  EXPECT_EQ(cost.bytes, kBytesPerTile + kBytesPerContributedCell * 40'000 + kBytesPerVertex * 10 +
                            kBytesPerRing * 3);
  // Overlapping polygons paint (and cost) each time.
  vector_map::VectorMap twice = Square(10.0);
  twice.free_space.push_back(twice.free_space.front());
  EXPECT_NEAR(static_cast<double>(CostOf(twice, Fusion()).cells), 80'000.0, 20.0);
}

TEST(TileBudgetTest, RefusesATileOfTooManyVerticesRingsOrPaintedCells) {
  BudgetOptions options;
  options.max_vertices_per_tile = 9;
  options.max_rings_per_tile = 2;
  options.max_painted_tiles_per_tile = 1.5;
  TileBudget budget(options, Fusion());
  const TileBudget::Source alpha{RobotId{"alpha"}, "p1", ""};
  EXPECT_THAT(
      RefusalOf(budget.Charge(alpha, {0, 0}, CostOf(Square(10.0, 2), Fusion()), kSteady)).detail,
      HasSubstr("10 vertices; a tile may have 9"));
  TileCost rings = CostOf(Square(1.0, 2), Fusion());
  rings.vertices = 9;
  EXPECT_THAT(RefusalOf(budget.Charge(alpha, {0, 0}, rings, kSteady)).detail,
              HasSubstr("3 free rings; a tile may have 2"));
  vector_map::VectorMap twice = Square(10.0);
  twice.free_space.push_back(twice.free_space.front());
  const auto painted = RefusalOf(budget.Charge(alpha, {0, 0}, CostOf(twice, Fusion()), kSteady));
  EXPECT_EQ(painted.reason, Refusal::kDecodedSize);
  EXPECT_THAT(painted.detail, HasSubstr("2.0 tiles' worth"));
  EXPECT_TRUE(std::holds_alternative<TileBudget::Charged>(
      budget.Charge(alpha, {0, 0}, CostOf(Square(10.0), Fusion()), kSteady)));
}

TEST(TileBudgetTest, ARobotsTilesTogetherStayWithinItsBudget) {
  BudgetOptions options;
  options.max_vertices_per_robot = 25;
  TileBudget budget(options, Fusion());
  const TileBudget::Source alpha{RobotId{"alpha"}, "p1", ""};
  EXPECT_TRUE(Evicted(budget.Charge(alpha, {0, 0}, Cost(1000), kSteady)).empty());
  EXPECT_TRUE(Evicted(budget.Charge(alpha, {0, 1}, Cost(1000), kSteady)).empty());
  // A new revision of a tile it holds replaces its cost.
  EXPECT_TRUE(Evicted(budget.Charge(alpha, {0, 1}, Cost(1000), kSteady)).empty());
  EXPECT_THAT(RefusalOf(budget.Charge(alpha, {0, 2}, Cost(1000), kSteady)).detail,
              HasSubstr("robot alpha to 30 vertices; a robot may hold 25"));
  budget.Release(RobotId{"alpha"}, {0, 0});
  EXPECT_TRUE(Evicted(budget.Charge(alpha, {0, 2}, Cost(1000), kSteady)).empty());
  EXPECT_EQ(budget.robot_cost(RobotId{"alpha"}).vertices, 20u);
}

TEST(TileBudgetTest, ThousandsOfIdsOfOneParticipantShareOneParticipantsBudget) {
  BudgetOptions options;
  options.max_bytes_per_robot = 10'000;
  options.robots_per_participant = 2.0;
  options.max_memory_bytes = 1'000'000;
  TileBudget budget(options, Fusion());
  size_t admitted = 0;
  for (int id = 0; id < 2000; ++id) {
    const TileBudget::Source source{RobotId{Numbered("r", id)}, "hostile", ""};
    const auto charged = budget.Charge(source, {id, 0}, Cost(1000), kSteady);
    if (std::holds_alternative<TileBudget::Charged>(charged)) {
      ++admitted;
    } else {
      EXPECT_EQ(std::get<TileBudget::Refused>(charged).reason, Refusal::kMemoryBudget);
    }
  }
  EXPECT_EQ(admitted, 20u);  // two robots' budgets, whatever the number of ids
  EXPECT_EQ(budget.participant_bytes("hostile"), 20'000u);
  EXPECT_EQ(budget.held_bytes(), 20'000u);
  // Another participant is not affected.
  EXPECT_TRUE(Evicted(budget.Charge({RobotId{"alpha"}, "honest", ""}, {0, 0}, Cost(1000), kSteady))
                  .empty());
}

TEST(TileBudgetTest, ParticipantsOfOneHostShareTheHostsBudget) {
  BudgetOptions options;
  options.max_bytes_per_robot = 10'000;
  options.robots_per_participant = 1.0;
  options.robots_per_host = 2.0;
  options.max_memory_bytes = 1'000'000;
  TileBudget budget(options, Fusion());
  size_t admitted = 0;
  for (int p = 0; p < 8; ++p) {
    for (int t = 0; t < 10; ++t) {
      const TileBudget::Source source{RobotId{Numbered("r", p)}, Numbered("p", p), "10.0.0.9"};
      if (std::holds_alternative<TileBudget::Charged>(
              budget.Charge(source, {p, t}, Cost(1000), kSteady))) {
        ++admitted;
      }
    }
  }
  EXPECT_EQ(admitted, 20u);
}

// Room for one robot's 4,000 bytes and half as much again, all robots together.
BudgetOptions SixThousandBytesForAll() {
  BudgetOptions options;
  options.max_bytes_per_robot = 4'000;
  options.robots_per_participant = 1.0;
  options.max_memory_bytes = 6'000;
  return options;
}

TEST(TileBudgetTest, WhenAllMemoryIsSpentTheNewestRobotsGiveWayFirst) {
  TileBudget budget(SixThousandBytesForAll(), Fusion());
  const TileBudget::Source old{RobotId{"established"}, "p1", ""};
  const TileBudget::Source mid{RobotId{"second"}, "p2", ""};
  const TileBudget::Source fresh{RobotId{"newest"}, "p3", ""};
  EXPECT_TRUE(Evicted(budget.Charge(old, {0, 0}, Cost(2000), kSteady)).empty());
  EXPECT_TRUE(Evicted(budget.Charge(mid, {1, 0}, Cost(2000), kSteady)).empty());
  EXPECT_TRUE(Evicted(budget.Charge(fresh, {2, 0}, Cost(2000), kSteady)).empty());
  // Full: the newest robot's next tile is refused, nobody older gives way for it.
  const auto refused = RefusalOf(budget.Charge(fresh, {2, 1}, Cost(1000), kSteady));
  EXPECT_EQ(refused.reason, Refusal::kMemoryBudget);
  EXPECT_THAT(refused.detail, HasSubstr("robots claimed after newest do not hold enough"));
  // The established robot's next tile makes the newest robot give way, not the second.
  EXPECT_THAT(Evicted(budget.Charge(old, {0, 1}, Cost(1000), kSteady)),
              ElementsAre(RobotId{"newest"}));
  budget.ReleaseRobot(RobotId{"newest"});
  EXPECT_EQ(budget.held_bytes(), 5'000u);
  EXPECT_TRUE(budget.TilesOf(RobotId{"newest"}).empty());
}

TEST(TileBudgetTest, MemoryOfSharedTilesCountsAgainstTheGlobalBudgetOnly) {
  TileBudget budget(SixThousandBytesForAll(), Fusion());
  const TileBudget::Source old{RobotId{"established"}, "p1", ""};
  const TileBudget::Source fresh{RobotId{"newest"}, "p2", ""};
  EXPECT_TRUE(Evicted(budget.Charge(old, {0, 0}, Cost(2000), kSteady)).empty());
  budget.SetSharedBytes(3'000);
  EXPECT_EQ(budget.held_bytes(), 5'000u);
  // 2,000 more would fit the robot's and the participant's budgets, not the global one.
  const auto refused = RefusalOf(budget.Charge(fresh, {1, 0}, Cost(2000), kSteady));
  EXPECT_EQ(refused.reason, Refusal::kMemoryBudget);
  EXPECT_THAT(refused.detail, HasSubstr("for tiles robots share"));
  budget.SetSharedBytes(1'000);
  EXPECT_TRUE(Evicted(budget.Charge(fresh, {1, 0}, Cost(2000), kSteady)).empty());
  EXPECT_EQ(budget.robot_cost(RobotId{"established"}).bytes, 2'000u);
}

TEST(TileBudgetTest, AParticipantsPaintingRateIsBounded) {
  BudgetOptions options;
  options.max_painted_tiles_per_second = 2.0;
  options.burst_painted_tiles = 4.0;
  TileBudget budget(options, Fusion());
  const TileCost one_tile = Cost(1000, 60'000);  // 1.5 tiles' worth of cells
  int admitted = 0;
  for (int i = 0; i < 10; ++i) {
    const TileBudget::Source source{RobotId{Numbered("r", i)}, "flooder", ""};
    if (std::holds_alternative<TileBudget::Charged>(
            budget.Charge(source, {i, 0}, one_tile, kSteady))) {
      ++admitted;
    }
  }
  EXPECT_EQ(admitted, 2);  // the burst of 4 tiles' worth
  // Two seconds later the bucket is full again (4, capped at the burst): two more.
  const TileBudget::Source later{RobotId{"r9"}, "flooder", ""};
  EXPECT_TRUE(std::holds_alternative<TileBudget::Charged>(
      budget.Charge(later, {9, 0}, one_tile, kSteady + seconds(2))));
  EXPECT_TRUE(std::holds_alternative<TileBudget::Charged>(
      budget.Charge(later, {9, 1}, one_tile, kSteady + seconds(2))));
  EXPECT_FALSE(std::holds_alternative<TileBudget::Charged>(
      budget.Charge(later, {9, 2}, one_tile, kSteady + seconds(2))));
}

}  // namespace
}  // namespace fleetmap::fusion
