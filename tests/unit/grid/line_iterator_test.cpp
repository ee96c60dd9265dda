#include "common/grid/line_iterator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <ostream>
#include <vector>

namespace fleetmap::grid {

void PrintTo(const CellIndex& cell, std::ostream* os) {
  *os << "(" << cell.x << ", " << cell.y << ")";
}

namespace {

using ::testing::ElementsAre;
using ::testing::ElementsAreArray;

static_assert(std::forward_iterator<LineIterator>);

std::vector<CellIndex> Cells(const CellIndex& from, const CellIndex& to) {
  std::vector<CellIndex> cells;
  for (const CellIndex cell : GridLine(from, to)) cells.push_back(cell);
  return cells;
}

// The contract written out independently of the error-term stepping: along the longer axis one
// cell per step; across it, the exact line's coordinate rounded, a tie rounded towards `to`.
std::vector<CellIndex> Reference(const CellIndex& from, const CellIndex& to) {
  const int dx = std::abs(to.x - from.x);
  const int dy = std::abs(to.y - from.y);
  const int sx = from.x < to.x ? 1 : -1;
  const int sy = from.y < to.y ? 1 : -1;
  const int n = std::max(dx, dy);
  // round(i * minor / n) with halves up, in integers: floor((2 * i * minor + n) / (2 * n)).
  const auto rounded = [n](int i, int minor) { return (2 * i * minor + n) / (2 * n); };
  std::vector<CellIndex> cells;
  for (int i = 0; i <= n; ++i) {
    if (n == 0) {
      cells.push_back(from);
    } else if (dx >= dy) {
      cells.push_back({from.x + sx * i, from.y + sy * rounded(i, dy)});
    } else {
      cells.push_back({from.x + sx * rounded(i, dx), from.y + sy * i});
    }
  }
  return cells;
}

TEST(LineIteratorTest, ASingleCellLineYieldsThatCell) {
  EXPECT_THAT(Cells({3, -2}, {3, -2}), ElementsAre(CellIndex{3, -2}));
  EXPECT_EQ(GridLine({3, -2}, {3, -2}).size(), 1);
}

TEST(LineIteratorTest, AxisAndDiagonalLinesInAllEightDirections) {
  EXPECT_THAT(Cells({0, 0}, {3, 0}),
              ElementsAre(CellIndex{0, 0}, CellIndex{1, 0}, CellIndex{2, 0}, CellIndex{3, 0}));
  EXPECT_THAT(Cells({0, 0}, {-2, 0}),
              ElementsAre(CellIndex{0, 0}, CellIndex{-1, 0}, CellIndex{-2, 0}));
  EXPECT_THAT(Cells({0, 0}, {0, 2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{0, 1}, CellIndex{0, 2}));
  EXPECT_THAT(Cells({0, 0}, {0, -2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{0, -1}, CellIndex{0, -2}));
  EXPECT_THAT(Cells({0, 0}, {2, 2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{1, 1}, CellIndex{2, 2}));
  EXPECT_THAT(Cells({0, 0}, {-2, 2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{-1, 1}, CellIndex{-2, 2}));
  EXPECT_THAT(Cells({0, 0}, {2, -2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{1, -1}, CellIndex{2, -2}));
  EXPECT_THAT(Cells({0, 0}, {-2, -2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{-1, -1}, CellIndex{-2, -2}));
}

// One line per octant, written out by hand: |dy| / |dx| = 2 / 5 and its mirror images.
TEST(LineIteratorTest, OneLinePerOctant) {
  EXPECT_THAT(Cells({0, 0}, {5, 2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{1, 0}, CellIndex{2, 1}, CellIndex{3, 1},
                          CellIndex{4, 2}, CellIndex{5, 2}));
  EXPECT_THAT(Cells({0, 0}, {2, 5}),
              ElementsAre(CellIndex{0, 0}, CellIndex{0, 1}, CellIndex{1, 2}, CellIndex{1, 3},
                          CellIndex{2, 4}, CellIndex{2, 5}));
  EXPECT_THAT(Cells({0, 0}, {-2, 5}),
              ElementsAre(CellIndex{0, 0}, CellIndex{0, 1}, CellIndex{-1, 2}, CellIndex{-1, 3},
                          CellIndex{-2, 4}, CellIndex{-2, 5}));
  EXPECT_THAT(Cells({0, 0}, {-5, 2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{-1, 0}, CellIndex{-2, 1}, CellIndex{-3, 1},
                          CellIndex{-4, 2}, CellIndex{-5, 2}));
  EXPECT_THAT(Cells({0, 0}, {-5, -2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{-1, 0}, CellIndex{-2, -1}, CellIndex{-3, -1},
                          CellIndex{-4, -2}, CellIndex{-5, -2}));
  EXPECT_THAT(Cells({0, 0}, {-2, -5}),
              ElementsAre(CellIndex{0, 0}, CellIndex{0, -1}, CellIndex{-1, -2}, CellIndex{-1, -3},
                          CellIndex{-2, -4}, CellIndex{-2, -5}));
  EXPECT_THAT(Cells({0, 0}, {2, -5}),
              ElementsAre(CellIndex{0, 0}, CellIndex{0, -1}, CellIndex{1, -2}, CellIndex{1, -3},
                          CellIndex{2, -4}, CellIndex{2, -5}));
  EXPECT_THAT(Cells({0, 0}, {5, -2}),
              ElementsAre(CellIndex{0, 0}, CellIndex{1, 0}, CellIndex{2, -1}, CellIndex{3, -1},
                          CellIndex{4, -2}, CellIndex{5, -2}));
}

TEST(LineIteratorTest, EveryShortLineIsTheRoundedExactLineWithBothEnds) {
  const CellIndex from{2, -3};
  for (int dx = -9; dx <= 9; ++dx) {
    for (int dy = -9; dy <= 9; ++dy) {
      const CellIndex to{from.x + dx, from.y + dy};
      SCOPED_TRACE(testing::Message() << "to (" << to.x << ", " << to.y << ")");
      const std::vector<CellIndex> cells = Cells(from, to);
      EXPECT_THAT(cells, ElementsAreArray(Reference(from, to)));
      ASSERT_FALSE(cells.empty());
      EXPECT_EQ(cells.front(), from);
      EXPECT_EQ(cells.back(), to);
      EXPECT_EQ(static_cast<int64_t>(cells.size()), GridLine(from, to).size());
      for (size_t i = 1; i < cells.size(); ++i) {
        EXPECT_EQ(
            std::max(std::abs(cells[i].x - cells[i - 1].x), std::abs(cells[i].y - cells[i - 1].y)),
            1)
            << "step " << i;
      }
    }
  }
}

TEST(LineIteratorTest, MirroredAndTransposedLinesHaveMirroredAndTransposedCells) {
  for (int dx = -7; dx <= 7; ++dx) {
    for (int dy = -7; dy <= 7; ++dy) {
      SCOPED_TRACE(testing::Message() << "to (" << dx << ", " << dy << ")");
      const std::vector<CellIndex> cells = Cells({0, 0}, {dx, dy});
      std::vector<CellIndex> mirrored_x, mirrored_y, transposed;
      for (const CellIndex& cell : cells) {
        mirrored_x.push_back({-cell.x, cell.y});
        mirrored_y.push_back({cell.x, -cell.y});
        transposed.push_back({cell.y, cell.x});
      }
      EXPECT_EQ(Cells({0, 0}, {-dx, dy}), mirrored_x);
      EXPECT_EQ(Cells({0, 0}, {dx, -dy}), mirrored_y);
      EXPECT_EQ(Cells({0, 0}, {dy, dx}), transposed);
    }
  }
}

// Ties go to the cell nearer `to`, so the two directions of (0, 0)-(2, 1) differ in the middle;
// without a tie a line and its reverse have the same cells.
TEST(LineIteratorTest, AReversedLineDiffersOnlyWhereTheLinePassesMidwayBetweenCells) {
  EXPECT_THAT(Cells({0, 0}, {2, 1}),
              ElementsAre(CellIndex{0, 0}, CellIndex{1, 1}, CellIndex{2, 1}));
  EXPECT_THAT(Cells({2, 1}, {0, 0}),
              ElementsAre(CellIndex{2, 1}, CellIndex{1, 0}, CellIndex{0, 0}));
  std::vector<CellIndex> backwards = Cells({5, 2}, {0, 0});
  std::reverse(backwards.begin(), backwards.end());
  EXPECT_EQ(backwards, Cells({0, 0}, {5, 2}));
}

TEST(LineIteratorTest, IteratorsCopyAndCompareLikeForwardIterators) {
  const GridLine line({0, 0}, {4, 1});
  LineIterator a = line.begin();
  LineIterator b = a;
  EXPECT_EQ(*a++, (CellIndex{0, 0}));
  EXPECT_EQ(*a, (CellIndex{1, 0}));
  EXPECT_EQ(*b, (CellIndex{0, 0}));  // a copy walks on its own
  EXPECT_NE(a, b);
  ++b;
  EXPECT_EQ(a, b);
  EXPECT_EQ(a->x, 1);
  EXPECT_EQ(std::distance(line.begin(), line.end()), 5);
  EXPECT_EQ(LineIterator(), line.end());
}

TEST(LineIteratorTest, LongLinesFarFromTheOriginEndAtTheirEnd) {
  const CellIndex from{-1000000000, 1000000000};
  const CellIndex to{from.x + 100000, from.y - 33333};
  int64_t count = 0;
  CellIndex last = from;
  for (const CellIndex cell : GridLine(from, to)) {
    last = cell;
    ++count;
  }
  EXPECT_EQ(count, 100001);
  EXPECT_EQ(last, to);
}

}  // namespace
}  // namespace fleetmap::grid
