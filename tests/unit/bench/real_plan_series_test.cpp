#include "bench/objects/real_plan_series.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bench/objects/real_plan_experiment.hpp"

namespace fleetmap::bench {
namespace {

// A 20 x 15 m hall: free inside, walls on the border.
grid::OccupancyGrid Hall() {
  grid::OccupancyGrid map(400, 300, 0.05, Pose2{}, grid::kFreeValue);
  for (int x = 0; x < 400; ++x) map.at(x, 0) = map.at(x, 299) = grid::kOccupiedValue;
  for (int y = 0; y < 300; ++y) map.at(0, y) = map.at(399, y) = grid::kOccupiedValue;
  return map;
}

RealPlanOptions Small() {
  RealPlanOptions options;
  options.width = 400;
  options.height = 300;
  options.maps = 3;
  options.pieces = 12;
  options.rows = 1;
  return options;
}

TEST(RealPlanSeriesTest, DrawsEveryPieceInEveryMapAtANewPlace) {
  const StatusOr<RealPlanSeries> series = MakeRealPlanSeries(Hall(), Small());
  ASSERT_TRUE(series.ok()) << series.status();
  ASSERT_EQ(series->maps.size(), 3u);
  EXPECT_EQ(series->unplaced, 0);
  for (size_t t = 0; t < series->maps.size(); ++t) {
    ASSERT_EQ(series->pieces[t].size(), 12u);
    for (const PlacedPiece& p : series->pieces[t]) {
      // Drawn: the piece's centre cell is occupied in its map (every shape is convex at its
      // centroid but the L, whose centroid lies in its corner's arm or next to it).
      const std::optional<grid::CellIndex> cell = series->maps[t].CellAt(p.centre);
      ASSERT_TRUE(cell.has_value());
      if (p.shape != PlanShape::kLShape) {
        EXPECT_EQ(series->maps[t].StateAt(cell->x, cell->y), grid::CellState::kOccupied);
      }
      EXPECT_GT(p.cells, 0);
    }
  }
  // The first four pieces are a row of desks, 1.3 m apart centre to centre.
  const std::vector<PlacedPiece>& first = series->pieces[0];
  for (int k = 0; k < 4; ++k) EXPECT_EQ(first[k].shape, PlanShape::kDesk);
  EXPECT_NEAR((first[1].centre - first[0].centre).norm(), 1.3, 0.051);
  // Pieces move between maps.
  EXPECT_GT((series->pieces[1][5].centre - series->pieces[0][5].centre).norm(), 0.3);
}

TEST(RealPlanSeriesTest, SameSeedSameSeries) {
  const StatusOr<RealPlanSeries> a = MakeRealPlanSeries(Hall(), Small());
  const StatusOr<RealPlanSeries> b = MakeRealPlanSeries(Hall(), Small());
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(a->maps == b->maps);
  RealPlanOptions other = Small();
  other.seed = 2;
  const StatusOr<RealPlanSeries> c = MakeRealPlanSeries(Hall(), other);
  ASSERT_TRUE(c.ok());
  EXPECT_FALSE(a->maps == c->maps);
}

TEST(RealPlanSeriesTest, ScoresSnapshotsAgainstPiecesOneToOne) {
  const StatusOr<RealPlanSeries> series = MakeRealPlanSeries(Hall(), Small());
  ASSERT_TRUE(series.ok());
  object_learning::LearnedModel model;
  // Two snapshots on map 0's first piece (only one may count), one far from everything.
  const Point2 piece = series->pieces[0][0].centre;
  model.snapshots.push_back({0, 0, piece + Point2(0.1, 0.0), {}});
  model.snapshots.push_back({0, 0, piece + Point2(0.0, 0.2), {}});
  model.snapshots.push_back({1, 0, Point2(-5.0, -5.0), {}});
  const RealPlanScore score = ScoreAgainstPieces(*series, model, 0.3);
  EXPECT_EQ(score.snapshots, 3);
  EXPECT_EQ(score.true_pieces, 36);
  EXPECT_EQ(score.matched, 1);
  EXPECT_DOUBLE_EQ(score.precision, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(score.recall, 1.0 / 36.0);
  EXPECT_EQ(score.spurious.size(), 2u);
  EXPECT_EQ(score.missed.size(), 35u);
}

TEST(RealPlanSeriesTest, TheLearnerFindsEveryPieceOfASmallSeries) {
  RealPlanOptions options = Small();
  options.pieces = 4;
  options.rows = 0;
  const StatusOr<RealPlanSeries> series = MakeRealPlanSeries(Hall(), options);
  ASSERT_TRUE(series.ok());
  const StatusOr<RealPlanResult> result =
      RunRealPlanExperiment(*series, object_learning::LearnOptions{});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->score.true_pieces, 12);
  EXPECT_EQ(result->score.matched, 12);
  EXPECT_DOUBLE_EQ(result->score.precision, 1.0);
  EXPECT_GE(result->num_objects, 4);  // mutual exclusion: the 4 pieces of a map are 4 objects
}

}  // namespace
}  // namespace fleetmap::bench
