#include "common/vector_map/free_space_extractor.hpp"

#include <array>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "common/vector_map/outline_simplifier.hpp"

namespace fleetmap::vector_map {
namespace {

// A hole around an unknown speck: its contour (through the free cells around it) fits a 3 x 3
// cell box, so the one cell it can enclose is within a cell of it, and dropping the hole is a
// simplification within any tolerance of a cell or more (Douglas-Peucker at the default sqrt(2)
// collapses such rings to a point or a line, which the extractor drops anyway). SLAM maps have
// thousands (intel_lab 4 100), so they are recognised before simplifying.
bool IsSpeckHole(const std::vector<cv::Point>& contour, double epsilon_cells) {
  if (epsilon_cells < 1.0) return false;
  const cv::Rect box = cv::boundingRect(contour);
  return box.width <= 3 && box.height <= 3;
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
  // The class of every (painted, near an edge, cell value) triple, looked up instead of
  // classified per cell: index (painted ? 512 : 0) + (near ? 256 : 0) + value byte.
  std::array<uint8_t, 1024> class_of{};
  for (int v = -128; v < 128; ++v) {
    const uint8_t byte = static_cast<uint8_t>(v);
    const grid::CellState state = grid::StateOf(static_cast<int8_t>(v), thresholds);
    class_of[byte] = state == grid::CellState::kFree       ? kIn
                     : state == grid::CellState::kOccupied ? kSolid
                                                           : kOut;
    class_of[256 + byte] = state == grid::CellState::kOccupied ? kAny : class_of[byte];
    class_of[512 + byte] = class_of[768 + byte] = state == grid::CellState::kFree ? kIn : kAny;
  }
  cv::Mat cls(rect.height, rect.width, CV_8UC1);
  unsigned seen = 0;  // bit c: some cell has class c
  for (int y = 0; y < rect.height; ++y) {
    uint8_t* row = cls.ptr<uint8_t>(y);
    const int8_t* cells =
        grid.data().data() + static_cast<size_t>(rect.y0 + y) * grid.width() + rect.x0;
    if (options.painted != nullptr) {
      const size_t offset = static_cast<size_t>(y) * rect.width;
      const uint8_t* painted = options.painted->data() + offset;
      const uint8_t* near =
          options.near_obstacles != nullptr ? options.near_obstacles->data() + offset : nullptr;
      for (int x = 0; x < rect.width; ++x) {
        const int key = (painted[x] != 0 ? 512 : 0) + (near != nullptr && near[x] != 0 ? 256 : 0) +
                        static_cast<uint8_t>(cells[x]);
        row[x] = class_of[key];
        seen |= 1u << row[x];
      }
    } else {
      for (int x = 0; x < rect.width; ++x) {
        row[x] = class_of[static_cast<uint8_t>(cells[x])];
        seen |= 1u << row[x];
      }
    }
  }
  const bool any = (seen & (1u << kIn)) != 0;
  const bool any_dont_care = (seen & (1u << kAny)) != 0;
  const bool any_solid = (seen & (1u << kSolid)) != 0;
  if (!any) return polygons;
  cv::Mat mask = cls == kIn;
  if (any_dont_care) {
    // Don't-care cells join the region only one cell or more away from a must-out or solid cell:
    // outlines simplified at epsilon then stray into don't-care cells rather than into those.
    cv::Mat near_out;
    cv::dilate(any_solid ? (cls == kOut) | (cls == kSolid) : cls == kOut, near_out,
               cv::Mat::ones(3, 3, CV_8UC1));
    mask |= (cls == kAny) & ~near_out;
    // Components without a free cell are not free space.
    cv::Mat labels;
    const int count = cv::connectedComponents(mask, labels, 8, CV_32S);
    std::vector<uint8_t> keep(static_cast<size_t>(count), 0);
    for (int y = 0; y < rect.height; ++y) {
      const uint8_t* row = cls.ptr<uint8_t>(y);
      const int* label = labels.ptr<int>(y);
      for (int x = 0; x < rect.width; ++x) keep[label[x]] |= row[x] == kIn ? 1 : 0;
    }
    for (int y = 0; y < rect.height; ++y) {
      uint8_t* row = mask.ptr<uint8_t>(y);
      const int* label = labels.ptr<int>(y);
      // keep[] is 0 or 1 (and 0 for the background label, whose cells are 0 already).
      for (int x = 0; x < rect.width; ++x) row[x] &= static_cast<uint8_t>(-keep[label[x]]);
    }
  }
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(mask, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  const OutlineSimplifier simplifier(any_solid ? cv::Mat(cls == kSolid) : cv::Mat(), epsilon_cells);
  auto convert = [&](const std::vector<cv::Point>& contour) {
    const std::vector<cv::Point> simplified = simplifier.Simplify(contour);
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
      if (IsSpeckHole(contours[child], epsilon_cells) &&
          !simplifier.AnyGuardedNear(contours[child])) {
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
