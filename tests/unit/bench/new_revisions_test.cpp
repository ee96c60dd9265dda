#include "bench/fleet/new_revisions.hpp"

#include <gtest/gtest.h>

namespace fleetmap::bench {
namespace {

TEST(NewRevisionsTest, TheFirstSampleOfEachRevisionIsNew) {
  NewRevisions revisions;
  EXPECT_TRUE(revisions.Take(TileId{0, 0}, 1));
  EXPECT_TRUE(revisions.Take(TileId{0, 0}, 2));
  EXPECT_TRUE(revisions.Take(TileId{1, 0}, 1));  // tiles are counted apart
}

TEST(NewRevisionsTest, ACopyWrittenAgainIsNotNewFusion) {
  NewRevisions revisions;
  ASSERT_TRUE(revisions.Take(TileId{2, 3}, 5));
  // A server that starts serving writes revision 5 again, with its old stamp.
  EXPECT_FALSE(revisions.Take(TileId{2, 3}, 5));
  // An older revision arriving late is not new either.
  EXPECT_FALSE(revisions.Take(TileId{2, 3}, 4));
  EXPECT_TRUE(revisions.Take(TileId{2, 3}, 6));
}

}  // namespace
}  // namespace fleetmap::bench
