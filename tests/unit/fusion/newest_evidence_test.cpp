#include "common/fusion/newest_evidence.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace fleetmap::fusion {
namespace {

using grid::kFreeValue;
using grid::kOccupiedValue;
using grid::kUnknownValue;

constexpr int kSide = 24;
constexpr size_t kCells = kSide * kSide;

grid::OccupancyGrid Empty() { return grid::OccupancyGrid(kSide, kSide, 0.05); }

// A contribution the test owns: its cells, their dates and its known span.
struct Owned {
  int slot = 0;
  std::vector<int8_t> values = std::vector<int8_t>(kCells, kUnknownValue);
  std::vector<uint32_t> dates = std::vector<uint32_t>(kCells, 0);
  size_t begin = 0;
  size_t end = kCells;

  DatedCells Dated() const { return DatedCells{slot, values.data(), dates.data(), begin, end}; }
};

std::vector<DatedCells> DatedOf(const std::vector<Owned>& owned, int skip = -1) {
  std::vector<DatedCells> out;
  for (const Owned& one : owned) {
    if (one.slot != skip) out.push_back(one.Dated());
  }
  return out;
}

// The fusion's rule, written out as TileFusion::FuseCells has it: newer evidence wins, at equal
// age an obstacle wins over free space, unknown cells say nothing.
void FuseFromScratch(const std::vector<DatedCells>& contributions, std::vector<int8_t>* values,
                     std::vector<uint32_t>* dates) {
  values->assign(kCells, kUnknownValue);
  dates->assign(kCells, 0);
  for (const DatedCells& contribution : contributions) {
    for (size_t i = contribution.begin; i < contribution.end; ++i) {
      const int8_t value = contribution.values[i];
      if (value == kUnknownValue) continue;
      const uint32_t at = contribution.dates[i];
      if (at > (*dates)[i] || (at == (*dates)[i] && value == kOccupiedValue)) {
        (*dates)[i] = at;
        (*values)[i] = value;
      }
    }
  }
}

void ExpectSameAsFromScratch(const NewestEvidence& newest, const std::vector<Owned>& owned,
                             int step) {
  std::vector<int8_t> values;
  std::vector<uint32_t> dates;
  FuseFromScratch(DatedOf(owned), &values, &dates);
  ASSERT_EQ(newest.cells().data(), values) << "step " << step;
  ASSERT_EQ(newest.dates(), dates) << "step " << step;
  // Each contribution left out, as the quarantine weighs it.
  for (const Owned& left_out : owned) {
    FuseFromScratch(DatedOf(owned, left_out.slot), &values, &dates);
    grid::OccupancyGrid without;
    std::vector<uint32_t> without_dates;
    newest.Without(left_out.slot, DatedOf(owned), &without, &without_dates);
    ASSERT_EQ(without.data(), values) << "step " << step << ", without slot " << left_out.slot;
    ASSERT_EQ(without_dates, dates) << "step " << step << ", without slot " << left_out.slot;
  }
}

// Random revisions of random contributions, told cell by cell, equal the fusion from scratch
// after every revision; so does each "without one contribution". Dates repeat and go back (an
// older stamp), cells turn unknown, spans shrink, and two slots share the holder mark past 255.
TEST(NewestEvidenceTest, ChangesToldCellByCellEqualTheFusionFromScratch) {
  std::mt19937 random(32);
  std::vector<Owned> owned(6);
  const int slots[] = {0, 1, 2, 5, 300, 301};
  for (size_t k = 0; k < owned.size(); ++k) owned[k].slot = slots[k];
  NewestEvidence newest(Empty());
  newest.Rebuild(DatedOf(owned));
  const int8_t states[] = {kUnknownValue, kFreeValue, kOccupiedValue};
  for (int step = 0; step < 400; ++step) {
    Owned& one = owned[random() % owned.size()];
    // Few dates, so that ties between contributions are common; 0 now and then.
    const uint32_t date = static_cast<uint32_t>(random() % 6);
    const size_t count = 1 + random() % 60;
    // Within the contribution's new span: outside it, its cells are unknown.
    const size_t begin = random() % (kCells / 4);
    const size_t end = kCells - random() % (kCells / 4);
    std::vector<int8_t> values = one.values;
    std::vector<uint32_t> dates = one.dates;
    for (size_t i = 0; i < kCells; ++i) {
      if (i < begin || i >= end) values[i] = kUnknownValue;
    }
    for (size_t n = 0; n < count; ++n) {
      const size_t i = begin + random() % (end - begin);
      values[i] = states[random() % 3];
    }
    for (size_t i = 0; i < kCells; ++i) {
      if (values[i] == one.values[i]) continue;
      dates[i] = date;
      newest.Change(one.slot, i, one.values[i], one.dates[i], values[i], date);
    }
    one.values = std::move(values);
    one.dates = std::move(dates);
    one.begin = begin;
    one.end = end;
    newest.Settle(DatedOf(owned));
    ExpectSameAsFromScratch(newest, owned, step);
    if (HasFatalFailure()) return;
  }
}

TEST(NewestEvidenceTest, RebuildTakesTheSetAsItIs) {
  std::vector<Owned> owned(2);
  owned[1].slot = 1;
  owned[0].values[3] = kOccupiedValue;
  owned[0].dates[3] = 7;
  owned[1].values[3] = kFreeValue;
  owned[1].dates[3] = 9;
  owned[1].values[4] = kFreeValue;  // dated 0: no evidence
  NewestEvidence newest(Empty());
  newest.Rebuild(DatedOf(owned));
  EXPECT_EQ(newest.cells().data()[3], kFreeValue);
  EXPECT_EQ(newest.dates()[3], 9u);
  EXPECT_EQ(newest.cells().data()[4], kUnknownValue);
  // Slot 1 leaves the set: the obstacle it had overruled is the newest again.
  owned.pop_back();
  newest.Rebuild(DatedOf(owned));
  EXPECT_EQ(newest.cells().data()[3], kOccupiedValue);
  EXPECT_EQ(newest.dates()[3], 7u);
}

}  // namespace
}  // namespace fleetmap::fusion
