#include "common/vector_map/skeleton.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "common/vector_map/segment_geometry.hpp"
#include "common/vector_map/wall_pockets.hpp"

namespace fleetmap::vector_map {
namespace {

std::array<bool, 256> BuildSimpleTable() {
  std::array<bool, 256> table{};
  for (int mask = 0; mask < 256; ++mask) {
    auto set = [&](int k) { return ((mask >> k) & 1) != 0; };
    auto count_components = [&](bool foreground, bool eight) {
      std::array<int, 8> label{};
      label.fill(-1);
      int components = 0;
      for (int start = 0; start < 8; ++start) {
        if (set(start) != foreground || label[start] >= 0) continue;
        // Background components only count if they touch the pixel through a 4-neighbour.
        std::array<int, 8> stack{};
        int top = 0;
        stack[top++] = start;
        label[start] = components;
        bool touches = foreground;
        while (top > 0) {
          const int k = stack[--top];
          if (k % 2 == 0) touches = true;
          for (int j = 0; j < 8; ++j) {
            if (set(j) != foreground || label[j] >= 0) continue;
            const int ddx = std::abs(kNeighbourDx[j] - kNeighbourDx[k]);
            const int ddy = std::abs(kNeighbourDy[j] - kNeighbourDy[k]);
            const bool adjacent = eight ? std::max(ddx, ddy) == 1 : ddx + ddy == 1;
            if (adjacent) {
              label[j] = components;
              stack[top++] = j;
            }
          }
        }
        if (touches) ++components;
      }
      return components;
    };
    const int count = std::popcount(static_cast<unsigned>(mask));
    table[mask] =
        count >= 2 && count_components(true, true) == 1 && count_components(false, false) == 1;
  }
  return table;
}

// A zeroed per-thread counter image, reused across calls (callers restore the zeros), so large
// grids do not pay for allocating and clearing a full image on every call.
std::vector<uint16_t>& ZeroedCounters(size_t size) {
  thread_local std::vector<uint16_t> counters;
  if (counters.size() < size) counters.resize(size, 0);
  return counters;
}

}  // namespace

const std::array<bool, 256>& SimplePointTable() {
  static const std::array<bool, 256> table = BuildSimpleTable();
  return table;
}

std::vector<int> DiscOffsets(const CellRaster& raster, double epsilon) {
  const double eps2 = ToleratedSquare(epsilon);
  const int r = static_cast<int>(std::ceil(epsilon));
  std::vector<std::tuple<int, int, int>> cells;  // (d^2, dy, dx)
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (dx * dx + dy * dy <= eps2) cells.emplace_back(dx * dx + dy * dy, dy, dx);
    }
  }
  std::sort(cells.begin(), cells.end());
  std::vector<int> offsets;
  offsets.reserve(cells.size());
  for (const auto& [d2, dy, dx] : cells) offsets.push_back(dy * raster.stride() + dx);
  return offsets;
}

std::vector<int> ThinToSkeleton(CellRaster& raster, double epsilon) {
  const CellRect& rect = raster.rect();
  const int stride = raster.stride();
  std::array<int, 8> offset{};
  for (int k = 0; k < 8; ++k) offset[k] = kNeighbourDy[k] * stride + kNeighbourDx[k];
  constexpr uint8_t kP = CellRaster::kDelimitation;
  std::vector<int> list;
  for (const int i : raster.occupied_near_rect()) {
    const int x = raster.X(i);
    const int y = raster.Y(i);
    if (!rect.Contains(x, y)) {
      raster.at(i) |= CellRaster::kAnchor;
      continue;
    }
    const bool keep = raster.Has(i, kP) || raster.Has(i + 1, kP) || raster.Has(i - 1, kP) ||
                      raster.Has(i + stride, kP) || raster.Has(i - stride, kP);
    if (keep) {
      raster.at(i) |= CellRaster::kSkeleton;
      list.push_back(i);
    }
  }
  // Wall pockets count as occupied (wall_pockets.hpp), so that a wall full of them thins to one
  // centre line instead of a ladder of rings.
  const size_t hollowed = list.size();
  for (const int i : WallPocketCells(raster)) {
    if (rect.Contains(raster.X(i), raster.Y(i))) {
      raster.at(i) |= CellRaster::kSkeleton;
      list.push_back(i);
    } else {
      raster.at(i) |= CellRaster::kAnchor;
    }
  }
  // Both parts are in row-major order (WallPocketCells returns its cells sorted).
  std::inplace_merge(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(hollowed),
                     list.end());
  const std::vector<int> window = DiscOffsets(raster, epsilon);
  // The default epsilon (sqrt(2) cells) gives the 3 x 3 block; a fixed-size copy lets the
  // compiler unroll the window loops, which run for every pixel.
  std::array<int, 9> block{};
  const bool is_block = window.size() == block.size();
  if (is_block) std::copy(window.begin(), window.end(), block.begin());
  auto for_window = [&](int i, auto&& f) {
    if (is_block) {
      for (const int o : block) f(i + o);
    } else {
      for (const int o : window) f(i + o);
    }
  };
  std::vector<uint16_t>& support = ZeroedCounters(raster.size());
  for (const int i : list) for_window(i, [&](int c) { ++support[c]; });
  // The low bits of support count skeleton pixels; the top two cache verdicts of the check below
  // so that repeated passes skip pixels whose verdict cannot have changed (the result is the same
  // as checking them all). kFixed: not removable; support only falls, so that is final. kClean:
  // the neighbourhood mask was neither simple nor a line end, which holds until a neighbour is
  // deleted (anchors never change), so each deletion clears kClean on its 8 neighbours.
  constexpr uint16_t kFixed = 0x8000;
  constexpr uint16_t kClean = 0x4000;
  constexpr uint16_t kCount = 0x3FFF;
  const bool cache = window.size() < kCount;
  auto removable = [&](int i) {
    bool ok = true;
    for_window(i, [&](int c) {
      ok &= !((support[c] & kCount) <= 1 && raster.Has(c, CellRaster::kOwned));
    });
    return ok;
  };
  constexpr uint8_t kBody = CellRaster::kSkeleton | CellRaster::kAnchor;
  const uint8_t* flags = &raster.at(0);
  auto mask_of = [&](int i) {
    int mask = 0;
    for (int k = 0; k < 8; ++k) mask |= ((flags[i + offset[k]] & kBody) != 0 ? 1 : 0) << k;
    return mask;
  };
  const auto& simple = SimplePointTable();
  static constexpr std::array<int, 4> kSides = {2, 6, 0, 4};  // N, S, E, W
  // Pixels that may still be deleted (kFixed ones leave it), in row-major order like `list`.
  std::vector<int> active = list;
  std::vector<int> candidates;
  bool changed = true;
  while (changed) {
    changed = false;
    for (const int side : kSides) {
      candidates.clear();
      for (const int i : active) {
        if (!(flags[i + offset[side]] & kBody)) candidates.push_back(i);
      }
      bool deleted = false;
      bool fixed = false;
      for (const int i : candidates) {
        if (support[i] & (kFixed | kClean)) continue;
        const int mask = mask_of(i);
        const bool line_end = mask != 0 && (mask & (mask - 1)) == 0;
        if (!(simple[mask] || line_end)) {
          if (cache) support[i] |= kClean;
          continue;
        }
        if (!removable(i)) {
          if (cache) support[i] |= kFixed;
          fixed = true;
          continue;
        }
        raster.at(i) &= static_cast<uint8_t>(~CellRaster::kSkeleton);
        for_window(i, [&](int c) { --support[c]; });
        for (const int o : offset) support[i + o] &= static_cast<uint16_t>(~kClean);
        deleted = true;
      }
      if (deleted) changed = true;
      if (deleted || fixed) {
        std::erase_if(active, [&](int i) {
          return !raster.Has(i, CellRaster::kSkeleton) || (support[i] & kFixed) != 0;
        });
      }
    }
  }
  std::erase_if(list, [&](int i) { return !raster.Has(i, CellRaster::kSkeleton); });
  for (const int i : list) {
    for_window(i, [&](int c) { support[c] = 0; });
  }
  return list;
}

}  // namespace fleetmap::vector_map
