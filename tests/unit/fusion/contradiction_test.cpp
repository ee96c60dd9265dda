#include "common/fusion/contradiction.hpp"

#include <gtest/gtest.h>

namespace fleetmap::fusion {
namespace {

using grid::kFreeValue;
using grid::kOccupiedValue;
using grid::kUnknownValue;
using grid::OccupancyGrid;

constexpr int kSide = 40;

OccupancyGrid Cells(int8_t value) { return OccupancyGrid(kSide, kSide, 0.05, Pose2{}, value); }

// The fleet's view: a free room with a wall along row 20, dated 100.
struct Fleet {
  OccupancyGrid cells = Cells(kFreeValue);
  std::vector<uint32_t> dates = std::vector<uint32_t>(kSide * kSide, 100);
  Fleet() {
    for (int x = 0; x < kSide; ++x) cells.at(x, 20) = kOccupiedValue;
  }
};

TEST(ContradictionTest, AFreeRoomWhereTheFleetHasAWallContradictsTheWholeWall) {
  const Fleet fleet;
  const OccupancyGrid robot = Cells(kFreeValue);
  const std::vector<uint32_t> dates(kSide * kSide, 200);
  const TileContradiction counted =
      CountContradiction(robot, dates, EstablishedCells{&fleet.cells, &fleet.dates}, 2);
  EXPECT_EQ(counted.established_seen, kSide);
  EXPECT_EQ(counted.contradicted, kSide);
  EXPECT_EQ(counted.min_x, 0);
  EXPECT_EQ(counted.max_x, kSide - 1);
  EXPECT_EQ(counted.min_y, 20);
  EXPECT_EQ(counted.max_y, 20);
}

TEST(ContradictionTest, TheSameWallWithinTheToleranceAgrees) {
  const Fleet fleet;
  OccupancyGrid robot = Cells(kFreeValue);
  for (int x = 0; x < kSide; ++x) robot.at(x, 22) = kOccupiedValue;  // 2 cells off
  const std::vector<uint32_t> dates(kSide * kSide, 200);
  EXPECT_EQ(CountContradiction(robot, dates, {&fleet.cells, &fleet.dates}, 2).contradicted, 0);
  // One cell less of tolerance, and the whole wall is contradicted.
  EXPECT_EQ(CountContradiction(robot, dates, {&fleet.cells, &fleet.dates}, 1).contradicted, kSide);
}

TEST(ContradictionTest, ScansGrazingAWallClearItsFaceWithoutContradictingIt) {
  // The fleet's wall is three cells thick (rows 19-21).
  Fleet fleet;
  for (int x = 0; x < kSide; ++x) {
    fleet.cells.at(x, 19) = kOccupiedValue;
    fleet.cells.at(x, 21) = kOccupiedValue;
  }
  // Scans along it clear its near face (row 19) and stop at the wall: behind is unknown to them.
  OccupancyGrid robot = Cells(kUnknownValue);
  for (int y = 0; y <= 19; ++y) {
    for (int x = 0; x < kSide; ++x) robot.at(x, y) = kFreeValue;
  }
  const std::vector<uint32_t> dates(kSide * kSide, 200);
  const TileContradiction grazing =
      CountContradiction(robot, dates, EstablishedCells{&fleet.cells, &fleet.dates}, 2);
  EXPECT_EQ(grazing.established_seen, kSide);
  EXPECT_EQ(grazing.contradicted, 0);
  // Free through the whole wall, unknown behind it: a hole in the fused map, counted whole.
  for (int y = 20; y <= 21; ++y) {
    for (int x = 0; x < kSide; ++x) robot.at(x, y) = kFreeValue;
  }
  EXPECT_EQ(CountContradiction(robot, dates, {&fleet.cells, &fleet.dates}, 2).contradicted,
            3 * kSide);
}

TEST(ContradictionTest, OlderFreeEvidenceAndUnknownCellsContradictNothing) {
  const Fleet fleet;
  const OccupancyGrid robot = Cells(kFreeValue);
  const std::vector<uint32_t> older(kSide * kSide, 50);  // newer evidence wins: the wall stays
  const TileContradiction counted =
      CountContradiction(robot, older, {&fleet.cells, &fleet.dates}, 2);
  EXPECT_EQ(counted.established_seen, kSide);
  EXPECT_EQ(counted.contradicted, 0);
  const std::vector<uint32_t> newer(kSide * kSide, 200);
  const TileContradiction unseen =
      CountContradiction(Cells(kUnknownValue), newer, {&fleet.cells, &fleet.dates}, 2);
  EXPECT_EQ(unseen.established_seen, 0);
  EXPECT_EQ(unseen.contradicted, 0);
}

TEST(ContradictionTest, ACellAnotherParticipantSawFreeSinceIsAConfirmedChange) {
  const Fleet fleet;
  const OccupancyGrid robot = Cells(kFreeValue);
  const std::vector<uint32_t> dates(kSide * kSide, 200);
  std::vector<uint32_t> confirmed(kSide * kSide, 0);
  for (int x = 0; x < 10; ++x) confirmed[20 * kSide + x] = 150;  // after the fleet's 100
  for (int x = 10; x < 20; ++x) confirmed[20 * kSide + x] = 90;  // before it: no confirmation
  const TileContradiction counted =
      CountContradiction(robot, dates, {&fleet.cells, &fleet.dates, &confirmed}, 2);
  EXPECT_EQ(counted.contradicted, kSide - 10);
  EXPECT_EQ(counted.min_x, 10);
}

}  // namespace
}  // namespace fleetmap::fusion
