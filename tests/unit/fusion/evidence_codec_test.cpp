#include "common/fusion/evidence_codec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fleetmap::fusion {
namespace {

using ::testing::HasSubstr;

constexpr int kSide = 40;

ContributionEvidence Sample() {
  ContributionEvidence evidence;
  const size_t count = static_cast<size_t>(kSide * kSide);
  evidence.cells.assign(count, grid::kUnknownValue);
  evidence.changed_at.assign(count, 0);
  for (size_t i = 0; i < count; ++i) {
    evidence.cells[i] =
        i % 7 == 0 ? grid::kOccupiedValue : (i % 3 == 0 ? grid::kFreeValue : grid::kUnknownValue);
    evidence.changed_at[i] = i < count / 2 ? 0x01020304u : 0xfffffffeu - static_cast<uint32_t>(i);
  }
  evidence.stamp = Timestamp(std::chrono::nanoseconds(1'700'000'000'123'456'789));
  return evidence;
}

TEST(EvidenceCodecTest, RoundTripsEveryCellAndDate) {
  const ContributionEvidence evidence = Sample();
  const auto bytes = EncodeEvidence(evidence);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  EXPECT_LT(bytes->size(), evidence.cells.size() * 5);  // compressed
  const auto decoded = DecodeEvidence(*bytes, kSide, "row");
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_EQ(decoded->cells, evidence.cells);
  EXPECT_EQ(decoded->changed_at, evidence.changed_at);
  EXPECT_EQ(decoded->stamp, evidence.stamp);
}

TEST(EvidenceCodecTest, RefusesAnotherTileGeometry) {
  const auto bytes = EncodeEvidence(Sample());
  ASSERT_TRUE(bytes.ok());
  const auto decoded = DecodeEvidence(*bytes, 200, "row");
  ASSERT_FALSE(decoded.ok());
  EXPECT_EQ(decoded.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(decoded.status().message(), HasSubstr("row: tile evidence has 40 cells per side"));
}

TEST(EvidenceCodecTest, RefusesDamagedBytes) {
  const auto bytes = EncodeEvidence(Sample());
  ASSERT_TRUE(bytes.ok());
  EXPECT_THAT(DecodeEvidence("", kSide, "row").status().message(), HasSubstr("not fleetmap"));
  EXPECT_EQ(DecodeEvidence(bytes->substr(0, bytes->size() / 2), kSide, "row").status().code(),
            StatusCode::kDataLoss);
  std::string other_version = *bytes;
  other_version[4] = 9;
  EXPECT_THAT(DecodeEvidence(other_version, kSide, "row").status().message(),
              HasSubstr("format 9"));
  std::string garbage = *bytes;
  for (size_t i = 17; i < garbage.size(); ++i) garbage[i] = static_cast<char>(i * 31);
  EXPECT_FALSE(DecodeEvidence(garbage, kSide, "row").ok());
}

TEST(EvidenceCodecTest, RefusesMismatchedLengths) {
  ContributionEvidence evidence = Sample();
  evidence.changed_at.pop_back();
  EXPECT_FALSE(EncodeEvidence(evidence).ok());
}

}  // namespace
}  // namespace fleetmap::fusion
