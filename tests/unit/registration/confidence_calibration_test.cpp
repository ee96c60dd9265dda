#include "common/registration/confidence_calibration.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace fleetmap::registration {
namespace {

TEST(ConfidenceCalibrationTest, InterpolatesBetweenKnotsAndHoldsBeyondThem) {
  const ConfidenceCalibration c({{0.2, 0.3}, {0.6, 0.9}});
  EXPECT_DOUBLE_EQ(c.Probability(0.0), 0.3);
  EXPECT_DOUBLE_EQ(c.Probability(0.4), 0.6);
  EXPECT_DOUBLE_EQ(c.Probability(1.0), 0.9);
}

TEST(ConfidenceCalibrationTest, FitIsMonotoneAndMatchesTheRates) {
  // Low scores right one time in four, high scores always right, one violator in between.
  std::vector<ConfidenceCalibration::Sample> samples;
  for (int i = 0; i < 40; ++i) samples.push_back({0.1 + 0.001 * i, i % 4 == 0});
  for (int i = 0; i < 40; ++i) samples.push_back({0.5 + 0.001 * i, i % 10 == 0});
  for (int i = 0; i < 40; ++i) samples.push_back({0.9 + 0.001 * i, true});
  const ConfidenceCalibration c = ConfidenceCalibration::Fit(samples, 20);
  for (size_t k = 1; k < c.knots().size(); ++k) {
    EXPECT_GT(c.knots()[k].score, c.knots()[k - 1].score);
    EXPECT_GE(c.knots()[k].probability, c.knots()[k - 1].probability);
  }
  // The violating middle pools with the low group: about (10 + 4) / 80 right.
  EXPECT_NEAR(c.Probability(0.12), 14.5 / 81.0, 1e-9);
  EXPECT_NEAR(c.Probability(0.95), 40.5 / 41.0, 1e-9);
  EXPECT_LT(c.Probability(0.95), 1.0);  // finite data never claims certainty
}

TEST(ConfidenceCalibrationTest, FitPoolsWhereTheRatesChangeNotOnAFixedGrid) {
  // 30 wrong placements, then 30 right ones: two blocks whatever their sizes. Pooled on a fixed
  // grid of 20, the second group would mix 10 of each and put a knot of rate 1/2 between them.
  std::vector<ConfidenceCalibration::Sample> samples;
  for (int i = 0; i < 30; ++i) samples.push_back({0.10 + 0.01 * i, false});
  for (int i = 0; i < 30; ++i) samples.push_back({0.60 + 0.01 * i, true});
  const ConfidenceCalibration c = ConfidenceCalibration::Fit(samples, 20);
  ASSERT_EQ(c.knots().size(), 2u);
  EXPECT_NEAR(c.knots()[0].probability, 0.5 / 31.0, 1e-9);
  EXPECT_NEAR(c.knots()[1].score, 0.745, 1e-9);
  EXPECT_NEAR(c.knots()[1].probability, 30.5 / 31.0, 1e-9);
}

TEST(ConfidenceCalibrationTest, OneNearMissAmongRightPlacementsStaysInTheirBlock) {
  // Wrong placements below 0.9, right ones above, and one wrong at 0.985 among the right ones
  // (a placement 3.1 cells off where 3 is right). The near miss is pooled with the right
  // placements around it, small blocks join the neighbour of nearer rate, and the scores just
  // above the wrong ones keep the high rate: the fit must not pull everything from 0.9 to 0.99
  // down to the wrong placements' rate.
  std::vector<ConfidenceCalibration::Sample> samples;
  for (int i = 0; i < 60; ++i) samples.push_back({0.30 + 0.01 * i, false});
  for (int i = 0; i < 100; ++i) samples.push_back({0.9001 + 0.00099 * i, true});
  samples.push_back({0.985, false});
  const ConfidenceCalibration c = ConfidenceCalibration::Fit(samples, 20);
  for (size_t k = 1; k < c.knots().size(); ++k) {
    EXPECT_GT(c.knots()[k].score, c.knots()[k - 1].score);
    EXPECT_GE(c.knots()[k].probability, c.knots()[k - 1].probability);
  }
  EXPECT_LT(c.Probability(0.5), 0.05);
  EXPECT_GT(c.Probability(0.96), 0.95);
  EXPECT_LT(c.Probability(0.999), 1.0);
}

TEST(ConfidenceCalibrationTest, BothDefaultsAreProbabilitiesThatGrowWithTheScore) {
  for (const ConfidenceCalibration* c :
       {&ConfidenceCalibration::Default(), &ConfidenceCalibration::DriftTolerant()}) {
    double previous = 0.0;
    for (double s = 0.0; s <= 1.0; s += 0.05) {
      const double p = c->Probability(s);
      EXPECT_GE(p, previous);
      EXPECT_LE(p, 1.0);
      previous = p;
    }
  }
}

}  // namespace
}  // namespace fleetmap::registration
