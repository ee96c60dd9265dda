#include "common/vector_map/free_space_extractor.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include <opencv2/imgproc.hpp>

#include "common/vector_map/outline_simplifier.hpp"

namespace fleetmap::vector_map {
namespace {

// A hole around an unknown speck: its contour (through the free cells around it) fits a 3 x 3
// cell box, so the one cell it can enclose is within a cell of it, and dropping the hole is a
// simplification within any tolerance of a cell or more (Douglas-Peucker at the default sqrt(2)
// collapses such rings to a point or a line, which the extractor drops anyway). SLAM maps have
// thousands (intel_lab 4 100), so they are recognised before simplifying.
bool IsSpeckHole(const cv::Rect& box, double epsilon_cells) {
  if (epsilon_cells < 1.0) return false;
  return box.width <= 3 && box.height <= 3;
}

// cv::boundingRect of a non-empty contour, without its InputArray dispatch (which cost more than
// the loop for the thousands of small holes of a SLAM map).
cv::Rect BoundingBox(const std::vector<cv::Point>& contour) {
  int x0 = contour.front().x;
  int y0 = contour.front().y;
  int x1 = x0;
  int y1 = y0;
  for (const cv::Point& p : contour) {
    x0 = std::min(x0, p.x);
    y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  return cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
}

// Fills, in the region mask, the speck holes the extractor would drop anyway, so that
// findContours neither traces nor returns them (most holes of a SLAM map's tiles are such specks).
// A speck here is a cell outside the region whose four neighbours are inside it (so not on the
// mask's border): a hole of one cell, whose contour runs through its 8 neighbours, so its bounding
// box fits 3 x 3 (IsSpeckHole) and that box grown by a cell fits the 5 x 5 cells around it. If no
// guarded (solid) cell lies there either, the hole is one the extraction below skips
// (IsSpeckHole && !AnyGuardedNear). Filling it changes no other contour: a border trace only ever
// steps over background pixels 4-connected to the background it follows, which never include a
// speck of another hole, and the speck's neighbours stay in the same foreground component; so the
// other contours, their order and their hierarchy are the same.
void FillSpeckHoles(const cv::Mat& cls, uint8_t solid, bool any_solid, cv::Mat& mask) {
  const int width = mask.cols;
  const int height = mask.rows;
  auto solid_near = [&](int x, int y) {
    for (int yy = std::max(y - 2, 0); yy <= std::min(y + 2, height - 1); ++yy) {
      const uint8_t* row = cls.ptr<uint8_t>(yy);
      for (int xx = std::max(x - 2, 0); xx <= std::min(x + 2, width - 1); ++xx) {
        if (row[xx] == solid) return true;
      }
    }
    return false;
  };
  // Filling a speck changes no other cell's test: its four neighbours are inside the region, so
  // none of them is a speck. The specks of a row can then be found from the mask as it was, a
  // block of cells at a time with a branch-free (vectorized) test, and blocks without one skipped.
  constexpr int kBlock = 16;
  for (int y = 1; y + 1 < height; ++y) {
    uint8_t* row = mask.ptr<uint8_t>(y);
    const uint8_t* above = mask.ptr<uint8_t>(y - 1);
    const uint8_t* below = mask.ptr<uint8_t>(y + 1);
    auto speck = [&](int x) {
      return row[x] == 0 && row[x - 1] != 0 && row[x + 1] != 0 && above[x] != 0 && below[x] != 0;
    };
    auto fill = [&](int x) {
      if (speck(x) && !(any_solid && solid_near(x, y))) row[x] = 255;
    };
    int x = 1;
    for (; x + kBlock < width; x += kBlock) {
      uint8_t any = 0;
      for (int k = x; k < x + kBlock; ++k) {
        any |= static_cast<uint8_t>((row[k] == 0) & (row[k - 1] != 0) & (row[k + 1] != 0) &
                                    (above[k] != 0) & (below[k] != 0));
      }
      if (any == 0) continue;
      for (int k = x; k < x + kBlock; ++k) fill(k);
    }
    for (; x + 1 < width; ++x) fill(x);
  }
}

// A (rows + 2) x (cols + 2) image whose one-cell frame holds `frame`. The inside is left as
// allocated: the caller writes every cell of it, so clearing it first would be wasted.
cv::Mat FramedImage(int rows, int cols, uint8_t frame) {
  cv::Mat image(rows + 2, cols + 2, CV_8UC1);
  std::memset(image.ptr<uint8_t>(0), frame, static_cast<size_t>(cols) + 2);
  std::memset(image.ptr<uint8_t>(rows + 1), frame, static_cast<size_t>(cols) + 2);
  for (int y = 1; y <= rows; ++y) {
    uint8_t* row = image.ptr<uint8_t>(y);
    row[0] = frame;
    row[cols + 1] = frame;
  }
  return image;
}

}  // namespace

std::vector<CellPolygon> ExtractFreeSpace(const grid::OccupancyGrid& grid, const CellRect& rect,
                                          const grid::StateThresholds& thresholds,
                                          const FreeSpaceOptions& options) {
  const double epsilon_cells = options.epsilon_cells;
  std::vector<CellPolygon> polygons;
  if (rect.empty()) return polygons;
  // kIn: free (must come back free); kOut: unknown and not painted (should not come back free;
  // the outline is simplified, so it may cut a corner into such cells); kSolid: occupied, not
  // painted and farther than epsilon from every obstacle edge (must never come back free: a
  // planner would drive through it; guarded exactly by the OutlineSimplifier, so it comes back
  // unknown); kAny: painted by an obstacle anyway, or occupied within epsilon of one.
  constexpr uint8_t kOut = 0;
  constexpr uint8_t kIn = 1;
  constexpr uint8_t kAny = 2;
  constexpr uint8_t kSolid = 3;
  // StateOf compares v / 100 with the thresholds, so the free values are a prefix [0, free_count)
  // of [0, 100] and the occupied ones a suffix [first_occupied, first_occupied + occupied_count);
  // a cell's class is then a few byte comparisons (vectorized) instead of a table look-up.
  int free_count = 0;
  int first_occupied = 101;
  for (int v = 0; v <= 100; ++v) {
    const grid::CellState state = grid::StateOf(static_cast<int8_t>(v), thresholds);
    if (state == grid::CellState::kFree) free_count = v + 1;
    if (state == grid::CellState::kOccupied) first_occupied = std::min(first_occupied, v);
  }
  const uint8_t free_below = static_cast<uint8_t>(free_count);
  const uint8_t occupied_from = static_cast<uint8_t>(first_occupied);
  const uint8_t occupied_count = static_cast<uint8_t>(101 - first_occupied);
  // The classes, framed by a ring of kEdge cells so that a cell's 8 neighbours are read without
  // bounds checks. Don't-care cells that join the region become kJoined, then kReached once a
  // free cell is found in their component. `mask` (the region, 255 inside) has the same frame, so
  // a cell's offset is the same in both.
  constexpr uint8_t kEdge = 4;
  constexpr uint8_t kJoined = 5;
  constexpr uint8_t kReached = 6;
  cv::Mat framed = FramedImage(rect.height, rect.width, kEdge);
  cv::Mat framed_mask = FramedImage(rect.height, rect.width, 0);
  const cv::Rect inside(1, 1, rect.width, rect.height);
  cv::Mat cls = framed(inside);
  cv::Mat mask = framed_mask(inside);
  // Without painted cells no cell is don't care (near_obstacles is not read).
  thread_local std::vector<uint8_t> zeros;
  zeros.assign(static_cast<size_t>(rect.width), 0);
  uint8_t any_in = 0;
  uint8_t any_dont_care_cell = 0;
  uint8_t any_solid_cell = 0;
  for (int y = 0; y < rect.height; ++y) {
    uint8_t* row = cls.ptr<uint8_t>(y);
    uint8_t* region = mask.ptr<uint8_t>(y);
    const uint8_t* cells = reinterpret_cast<const uint8_t*>(grid.data().data()) +
                           static_cast<size_t>(rect.y0 + y) * grid.width() + rect.x0;
    const size_t offset = static_cast<size_t>(y) * rect.width;
    const bool has_painted = options.painted != nullptr;
    const uint8_t* painted = has_painted ? options.painted->data() + offset : zeros.data();
    const uint8_t* near = has_painted && options.near_obstacles != nullptr
                              ? options.near_obstacles->data() + offset
                              : zeros.data();
    // Byte masks (0 or 0xFF), no short-circuit and a local width (a byte store may alias
    // `rect`), so that the loop vectorizes.
    const int width = rect.width;
    for (int x = 0; x < width; ++x) {
      const uint8_t v = cells[x];
      const uint8_t is_free = v < free_below ? 0xFF : 0;
      const uint8_t is_occupied =
          static_cast<uint8_t>(v - occupied_from) < occupied_count ? 0xFF : 0;
      const uint8_t dont_care =
          (painted[x] != 0 ? 0xFF : 0) | ((near[x] != 0 ? 0xFF : 0) & is_occupied);
      const uint8_t any_cell = static_cast<uint8_t>(~is_free & dont_care);
      const uint8_t solid_cell = static_cast<uint8_t>(~is_free & ~dont_care & is_occupied);
      row[x] = static_cast<uint8_t>((is_free & kIn) | (any_cell & kAny) | (solid_cell & kSolid));
      region[x] = is_free;
      any_in |= is_free;
      any_dont_care_cell |= any_cell;
      any_solid_cell |= solid_cell;
    }
  }
  const bool any = any_in != 0;
  const bool any_dont_care = any_dont_care_cell != 0;
  const bool any_solid = any_solid_cell != 0;
  if (!any) return polygons;
  if (any_dont_care) {
    // Don't-care cells join the region only one cell or more away from a must-out or solid cell
    // (none among their 8 neighbours in the rectangle): outlines simplified at epsilon then stray
    // into don't-care cells rather than into those.
    const ptrdiff_t step = static_cast<ptrdiff_t>(framed.step);
    const std::array<ptrdiff_t, 8> around = {-step - 1, -step,    -step + 1, -1,
                                             1,         step - 1, step,      step + 1};
    thread_local std::vector<uint8_t*> joined;
    thread_local std::vector<uint8_t*> reached;
    joined.clear();
    reached.clear();
    for (int y = 0; y < rect.height; ++y) {
      uint8_t* row = cls.ptr<uint8_t>(y);
      uint8_t* const row_end = row + rect.width;
      // Don't-care cells are sparse: memchr skips to the next one.
      for (uint8_t* cell = row; cell < row_end; ++cell) {
        cell = static_cast<uint8_t*>(std::memchr(cell, kAny, static_cast<size_t>(row_end - cell)));
        if (cell == nullptr) break;
        // One bit test per neighbour: bit c of kOutOrSolid says whether class c is one of them.
        constexpr unsigned kOutOrSolid = 1u << kOut | 1u << kSolid;
        unsigned near_out = 0;
        for (const ptrdiff_t d : around) near_out |= kOutOrSolid >> cell[d];
        if (near_out & 1u) continue;
        *cell = kJoined;
        joined.push_back(cell);
      }
    }
    // Components (8-connected) without a free cell are not free space: the joined cells are
    // flooded from the free ones, and those not reached stay out.
    for (uint8_t* cell : joined) {
      bool next_to_free = false;
      for (const ptrdiff_t d : around) next_to_free |= cell[d] == kIn;
      if (next_to_free) {
        *cell = kReached;
        reached.push_back(cell);
        framed_mask.data[cell - framed.data] = 255;
      }
    }
    // Usually every joined cell is next to a free one: then none is left to flood.
    if (reached.size() == joined.size()) reached.clear();
    while (!reached.empty()) {
      uint8_t* cell = reached.back();
      reached.pop_back();
      for (const ptrdiff_t d : around) {
        if (cell[d] != kJoined) continue;
        cell[d] = kReached;
        reached.push_back(cell + d);
        framed_mask.data[cell + d - framed.data] = 255;
      }
    }
  }
  if (epsilon_cells >= 1.0) FillSpeckHoles(cls, kSolid, any_solid, mask);
  // Per-thread, so that findContours resizes the contours of the previous call in place (it
  // overwrites every one) instead of allocating hundreds of small vectors.
  thread_local std::vector<std::vector<cv::Point>> contours;
  thread_local std::vector<cv::Vec4i> hierarchy;
  cv::findContours(mask, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  const OutlineSimplifier simplifier(any_solid ? cv::Mat(cls == kSolid) : cv::Mat(), epsilon_cells);
  std::vector<cv::Point> simplified;
  auto convert = [&](const std::vector<cv::Point>& contour) {
    simplifier.Simplify(contour, &simplified);
    std::vector<Point2> ring;
    ring.reserve(simplified.size());
    for (const cv::Point& p : simplified) ring.emplace_back(rect.x0 + p.x, rect.y0 + p.y);
    return ring;
  };
  for (size_t i = 0; i < contours.size(); ++i) {
    if (hierarchy[i][3] >= 0) continue;  // a hole; handled with its parent
    CellPolygon polygon;
    polygon.outer = convert(contours[i]);
    for (int child = hierarchy[i][2]; child >= 0; child = hierarchy[child][0]) {
      const cv::Rect box = BoundingBox(contours[child]);
      if (IsSpeckHole(box, epsilon_cells) && !simplifier.AnyGuardedNear(box)) {
        continue;  // what simplifying it would give: a hole too small to keep (below)
      }
      auto hole = convert(contours[child]);
      // A hole simplified to a point or a line encloses no cell (and no solid one,
      // OutlineSimplifier checked that): it would cost bytes for nothing.
      if (hole.size() < 3) continue;
      polygon.holes.push_back(std::move(hole));
    }
    polygons.push_back(std::move(polygon));
  }
  return polygons;
}

}  // namespace fleetmap::vector_map
