#include "common/core/number_format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace fleetmap {
namespace {

TEST(NumberFormatTest, CleanNumberDropsArithmeticNoiseAndKeepsGivenDigits) {
  EXPECT_EQ(CleanNumber(0.05), "0.05");
  EXPECT_EQ(CleanNumber(-3 * 12.8), "-38.4");  // -38.400000000000006 in binary
  EXPECT_EQ(CleanNumber(1687 * 0.025), "42.175");
  EXPECT_EQ(CleanNumber(0.1 + 0.2), "0.3");
  EXPECT_EQ(CleanNumber(1.2e-17), "0");
  EXPECT_EQ(CleanNumber(-1e-17), "0");
  EXPECT_EQ(CleanNumber(-12.345), "-12.345");
  EXPECT_EQ(CleanNumber(100.0), "100");
  // Digits a person gave stay, even past nine decimals.
  EXPECT_EQ(CleanNumber(0.0123456789012), "0.0123456789012");
  // A float32 widened to double is not noise: it is what the caller holds (DoubleFromFloat).
  EXPECT_EQ(CleanNumber(static_cast<double>(0.05F)), "0.05000000074505806");
  EXPECT_EQ(CleanNumber(std::numeric_limits<double>::infinity()), "inf");
}

TEST(NumberFormatTest, CleanNumberReadsBackWithinAPicometre) {
  for (const double value : {-38.400000000000006, 42.175000000000004, 1e6 + 0.3, 1e-9, 7.0 / 3}) {
    EXPECT_NEAR(std::stod(CleanNumber(value)), value, 1e-12 * std::max(1.0, std::abs(value)))
        << value;
  }
}

TEST(NumberFormatTest, FixedNumberRoundsAndDropsTrailingZeros) {
  EXPECT_EQ(FixedNumber(50.00000089, 3), "50");
  EXPECT_EQ(FixedNumber(0.560381, 3), "0.56");
  EXPECT_EQ(FixedNumber(194.006, 1), "194");
  EXPECT_EQ(FixedNumber(194.06, 1), "194.1");
  EXPECT_EQ(FixedNumber(-0.0001, 3), "0");
  EXPECT_EQ(FixedNumber(12.0, 0), "12");
  EXPECT_EQ(FixedNumber(1200.0, 2), "1200");
}

TEST(NumberFormatTest, RoundToDecimalsGivesTheDoubleNearestTheDecimal) {
  EXPECT_EQ(RoundToDecimals(42.175000000000004, 6), 42.175);
  EXPECT_EQ(RoundToDecimals(-38.400000000000006, 6), -38.4);
  EXPECT_EQ(RoundToDecimals(0.1234564, 6), 0.123456);
  EXPECT_EQ(RoundToDecimals(-1e-9, 6), 0.0);
  EXPECT_FALSE(std::signbit(RoundToDecimals(-1e-9, 6)));
  EXPECT_EQ(RoundToDecimals(1e300, 6), 1e300);  // too large for six decimals: unchanged
  EXPECT_TRUE(std::isnan(RoundToDecimals(std::nan(""), 6)));
}

TEST(NumberFormatTest, DoubleFromFloatIsTheDecimalTheFloatStoodFor) {
  EXPECT_EQ(DoubleFromFloat(0.05F), 0.05);
  EXPECT_EQ(DoubleFromFloat(0.025F), 0.025);
  EXPECT_EQ(DoubleFromFloat(0.1F), 0.1);
  EXPECT_EQ(DoubleFromFloat(12.8F), 12.8);
  EXPECT_EQ(DoubleFromFloat(0.5F), 0.5);
  EXPECT_EQ(static_cast<float>(DoubleFromFloat(0.05F)), 0.05F);  // the same float again
  EXPECT_TRUE(std::isinf(DoubleFromFloat(std::numeric_limits<float>::infinity())));
}

}  // namespace
}  // namespace fleetmap
