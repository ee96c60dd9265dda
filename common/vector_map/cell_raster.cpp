#include "common/vector_map/cell_raster.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

#include "common/core/check.hpp"

namespace fleetmap::vector_map {
namespace {

// The smallest grid value read as occupied (grid::StateOf: v in [0, 100] and v / 100 > threshold),
// or 101 if none is.
int FirstOccupiedValue(const grid::StateThresholds& thresholds) {
  for (int v = 0; v <= 100; ++v) {
    if (v / 100.0 > thresholds.occupied) return v;
  }
  return 101;
}

// Appends the indices of cells in [begin, end) of `row` (raster index `base` at begin) with any of
// `bits` set, in order, eight cells at a time (assumes a little-endian host, as x86 and ARM are).
void CollectRow(const uint8_t* row, int begin, int end, int base, uint8_t bits,
                std::vector<int>& out) {
  constexpr uint64_t kLow7 = 0x7F7F7F7F7F7F7F7FULL;
  constexpr uint64_t kHigh = 0x8080808080808080ULL;
  const uint64_t word_bits = 0x0101010101010101ULL * bits;
  int x = begin;
  for (; x + 8 <= end; x += 8) {
    if (x + 32 <= end) {  // skip empty stretches 32 cells at a time
      uint64_t words[4];
      std::memcpy(words, row + x, sizeof(words));
      if (((words[0] | words[1] | words[2] | words[3]) & word_bits) == 0) {
        x += 24;
        continue;
      }
    }
    uint64_t word;
    std::memcpy(&word, row + x, sizeof(word));
    const uint64_t hit = word & word_bits;
    if (hit == 0) continue;
    // The top bit of each byte of `nonzero` says whether that byte of `hit` is nonzero; bytes
    // are in memory order (little-endian), so the lowest set bit is the leftmost cell.
    uint64_t nonzero = (((hit & kLow7) + kLow7) | hit) & kHigh;
    while (nonzero != 0) {
      out.push_back(base + x + std::countr_zero(nonzero) / 8);
      nonzero &= nonzero - 1;
    }
  }
  for (; x < end; ++x) {
    if (row[x] & bits) out.push_back(base + x);
  }
}

// The flag image's storage, kept per thread between calls: a large grid then costs no page faults
// for a fresh image on every call (the image is fully rewritten anyway).
std::vector<uint8_t>& FlagPool() {
  thread_local std::vector<uint8_t> pool;
  return pool;
}

}  // namespace

CellRaster::~CellRaster() {
  if (FlagPool().capacity() < flags_.capacity()) FlagPool().swap(flags_);
}

CellRaster::CellRaster(const grid::OccupancyGrid& grid, const CellRect& rect, int margin,
                       const grid::StateThresholds& thresholds)
    : rect_(rect) {
  FLEETMAP_CHECK(margin >= 1);  // the rectangle grown by one then lies inside the scan for P below
  const int pad = margin + 1;
  x0_ = rect.x0 - pad;
  y0_ = rect.y0 - pad;
  stride_ = rect.width + 2 * pad;
  rows_ = rect.height + 2 * pad;
  flags_.swap(FlagPool());
  flags_.resize(static_cast<size_t>(stride_) * rows_);
  const int first = FirstOccupiedValue(thresholds);
  const uint8_t span = static_cast<uint8_t>(first <= 100 ? 100 - first : 0);
  const int gx0 = std::max(x0_, 0);
  const int gx1 = std::min(x0_ + stride_, grid.width());
  std::vector<uint8_t> row_any(static_cast<size_t>(rows_), 0);
  for (int r = 0; r < rows_; ++r) {
    uint8_t* out = flags_.data() + static_cast<size_t>(r) * stride_;
    const int y = y0_ + r;
    if (y < 0 || y >= grid.height() || gx0 >= gx1 || first > 100) {
      std::memset(out, 0, static_cast<size_t>(stride_));
      continue;
    }
    std::memset(out, 0, static_cast<size_t>(gx0 - x0_));
    std::memset(out + (gx1 - x0_), 0, static_cast<size_t>(x0_ + stride_ - gx1));
    const int8_t* in = grid.data().data() + static_cast<size_t>(y) * grid.width();
    uint8_t any = 0;
    // (v - first) as an unsigned byte is <= span exactly for first <= v <= 100; vectorizes.
    for (int x = gx0; x < gx1; ++x) {
      const uint8_t occupied =
          static_cast<uint8_t>(static_cast<uint8_t>(in[x] - first) <= span ? 1 : 0);
      out[x - x0_] = occupied;
      any |= occupied;
    }
    row_any[r] = any;
  }
  // P: occupied cells with a 4-neighbour not occupied (the outermost ring is left without P).
  // The same scan of a row lists the occupied cells of the rectangle grown by one (that row's
  // occupied cells, clipped) and its P points inside the rectangle (owned), in row-major order.
  std::vector<int> occupied_row;
  const int near_x0 = rect.x0 - 1 - x0_;
  const int near_x1 = rect.x0 + rect.width + 1 - x0_;
  const int rect_x0 = rect.x0 - x0_;
  const int rect_x1 = rect.x0 + rect.width - x0_;
  for (int r = 1; r + 1 < rows_; ++r) {
    if (!row_any[r]) continue;
    uint8_t* row = flags_.data() + static_cast<size_t>(r) * stride_;
    occupied_row.clear();
    CollectRow(row, 1, stride_ - 1, 0, kOccupied, occupied_row);
    for (const int x : occupied_row) {
      const uint8_t all = row[x - 1] & row[x + 1] & row[x - stride_] & row[x + stride_] & 1;
      if (!all) row[x] |= kDelimitation;
    }
    const int y = y0_ + r;
    if (y < rect.y0 - 1 || y > rect.y0 + rect.height) continue;
    const bool in_rect_rows = y >= rect.y0 && y < rect.y0 + rect.height;
    const int base = r * stride_;
    for (const int x : occupied_row) {
      if (x < near_x0 || x >= near_x1) continue;
      occupied_.push_back(base + x);
      if (in_rect_rows && x >= rect_x0 && x < rect_x1 && (row[x] & kDelimitation)) {
        row[x] |= kOwned;
        owned_.push_back(base + x);
      }
    }
  }
}

}  // namespace fleetmap::vector_map
