#include "common/registration/registration.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/core/number_format.hpp"
#include "common/registration/confidence_calibration.hpp"
#include "common/registration/placement_verifier.hpp"

namespace fleetmap::registration {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// Candidates are looked for only above this fraction of the best coarse score: a lower floor
// would let the search visit most of the space again.
constexpr double kCandidateFloor = 0.5;
// A second placement verifying at this fraction of the best or less leaves the match fully
// distinct (Registration::score).
constexpr double kDistinctRatio = 0.7;
// Candidates that get the fine refinement stages after a first verification.
constexpr size_t kFullyRefined = 4;
// ... and beyond those, every candidate whose first verification reaches this share of the
// best's: below it a candidate can be neither a shifted twin (max_peak_ratio, 85 % of the best's
// value) nor a turned one (half the best's agreeing cells at nearly its consistency, about 35 %
// of its value), even allowing for the coarser refinement it was screened at.
constexpr double kRivalShare = 0.35;

std::string Num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", value);
  return buffer;
}

std::string Fixed(double value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

// What the cells where the best placement and its twin disagree say, for a refusal.
std::string TellingApart(const std::optional<Discrimination>& untold, double resolution,
                         const RegistrationOptions& options) {
  if (!untold) return "";
  const Discrimination& d = *untold;
  return std::string("; where the two disagree, ")
      .append(Num(d.for_first * resolution))
      .append(" m of walls favour the best and ")
      .append(Num(d.for_second * resolution))
      .append(" m the other (")
      .append(Num(options.symmetry_telling_m))
      .append(" m needed, at most ")
      .append(Num(100.0 * options.symmetry_telling_ratio))
      .append(" % against)");
}

// A grid reduced by an integer factor: a coarse cell is occupied when any of its cells is.
struct CoarseOccupancy {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> occupied;  // row-major, row 0 at the origin
  std::vector<uint8_t> free;      // some cell free, none occupied
};

CoarseOccupancy Reduce(const grid::OccupancyGrid& g, int factor,
                       const grid::StateThresholds& thresholds) {
  CoarseOccupancy out;
  out.width = (g.width() + factor - 1) / factor;
  out.height = (g.height() + factor - 1) / factor;
  out.occupied.assign(static_cast<size_t>(out.width) * out.height, 0);
  out.free.assign(out.occupied.size(), 0);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const size_t i = static_cast<size_t>(y / factor) * out.width + x / factor;
      const grid::CellState state = g.StateAt(x, y, thresholds);
      if (state == grid::CellState::kOccupied) out.occupied[i] = 1;
      if (state == grid::CellState::kFree) out.free[i] = 1;
    }
  }
  for (size_t i = 0; i < out.free.size(); ++i) {
    if (out.occupied[i]) out.free[i] = 0;
  }
  return out;
}

// What a point of B scores on each cell of A: exp(-d^2 / 2 sigma^2) of the distance d (cells) to
// A's nearest occupied cell, less free_penalty * (1 - that) on A's free cells, so that B's walls
// crossing A's known free space cost what they would contradict.
cv::Mat LikelihoodField(int width, int height, const std::vector<uint8_t>& occupied,
                        const std::vector<uint8_t>& free, double sigma, double free_penalty) {
  cv::Mat free_mask(height, width, CV_8U);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      free_mask.at<uint8_t>(y, x) = occupied[static_cast<size_t>(y) * width + x] ? 0 : 255;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(free_mask, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat field(height, width, CV_32F);
  const float k = static_cast<float>(-0.5 / (sigma * sigma));
  const float penalty = static_cast<float>(free_penalty);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float d = distance.at<float>(y, x);
      const float near = std::exp(k * d * d);
      field.at<float>(y, x) =
          free[static_cast<size_t>(y) * width + x] ? near - penalty * (1.0f - near) : near;
    }
  }
  return field;
}

// Level h holds, at (x, y), the max of the field over [x, x + 2^h) x [y, y + 2^h) (0 outside the
// field). The levels are padded by `pad` cells on every side, so that every lookup the search
// makes (B's cells never reach further than `pad` beyond the field) is a plain array read.
class MaxPyramid {
 public:
  MaxPyramid(const cv::Mat& field, int levels, int pad)
      : pad_(pad), stride_(field.cols + 2 * pad), rows_(field.rows + 2 * pad) {
    levels_.resize(levels);
    levels_[0].assign(static_cast<size_t>(stride_) * rows_, 0.0f);
    for (int y = 0; y < field.rows; ++y) {
      for (int x = 0; x < field.cols; ++x) levels_[0][Offset(x, y)] = field.at<float>(y, x);
    }
    for (int h = 1; h < levels; ++h) {
      const int s = 1 << (h - 1);
      const std::vector<float>& below = levels_[h - 1];
      std::vector<float>& level = levels_[h];
      level.assign(below.size(), 0.0f);
      for (int iy = 0; iy < rows_; ++iy) {
        for (int ix = 0; ix < stride_; ++ix) {
          const size_t i = static_cast<size_t>(iy) * stride_ + ix;
          float m = below[i];
          if (ix + s < stride_) m = std::max(m, below[i + s]);
          if (iy + s < rows_) {
            m = std::max(m, below[i + static_cast<size_t>(s) * stride_]);
            if (ix + s < stride_) m = std::max(m, below[i + static_cast<size_t>(s) * stride_ + s]);
          }
          level[i] = m;
        }
      }
    }
  }

  // The array index of field cell (x, y), and the linear step of (dx, dy).
  size_t Offset(int x, int y) const {
    return static_cast<size_t>(y + pad_) * stride_ + static_cast<size_t>(x + pad_);
  }
  ptrdiff_t Step(int dx, int dy) const { return static_cast<ptrdiff_t>(dy) * stride_ + dx; }
  const float* Level(int level) const { return levels_[level].data(); }
  int levels() const { return static_cast<int>(levels_.size()); }

 private:
  int pad_;
  int stride_;
  int rows_;
  std::vector<std::vector<float>> levels_;
};

struct CellPoint {
  int x;
  int y;
};

// B's coarse points rotated by one yaw about their centroid, rounded to cells.
struct RotatedPoints {
  double yaw = 0.0;
  std::vector<CellPoint> points;
  std::vector<ptrdiff_t> steps;  // the points as pyramid index steps
  int min_x = 0, max_x = 0, min_y = 0, max_y = 0;
};

struct Candidate {
  int yaw_index = 0;
  int x = 0;
  int y = 0;
  int level = 0;
  float score = 0.0f;
};

// Cartographer-style branch and bound over translations, for every yaw at once.
class BranchAndBound {
 public:
  BranchAndBound(const MaxPyramid& pyramid, const std::vector<RotatedPoints>& rotations,
                 int field_width, int field_height)
      : pyramid_(pyramid), rotations_(rotations), width_(field_width), height_(field_height) {}

  // Up to `count` leaves, best first, that are pairwise clearly different (`same(l, r)` false),
  // each scoring above `floor` and above `relative_floor` times the best: one pass, pruned by
  // the count-th best kept so far. Of leaves that are not clearly different, the best is kept.
  template <typename Same>
  std::vector<Candidate> SearchTop(float floor, float relative_floor, int count,
                                   const Same& same) const {
    const int top = pyramid_.levels() - 1;
    const int step = 1 << top;
    std::vector<Candidate> roots;
    for (int r = 0; r < static_cast<int>(rotations_.size()); ++r) {
      const RotatedPoints& rot = rotations_[r];
      for (int y = -rot.max_y; y <= height_ - 1 - rot.min_y; y += step) {
        for (int x = -rot.max_x; x <= width_ - 1 - rot.min_x; x += step) {
          Candidate c{r, x, y, top, 0.0f};
          c.score = Score(c);
          if (c.score > floor) roots.push_back(c);
        }
      }
    }
    std::sort(roots.begin(), roots.end(),
              [](const Candidate& l, const Candidate& r) { return l.score > r.score; });
    Top<Same> kept{floor, relative_floor, count, same, {}};
    for (const Candidate& root : roots) {
      if (root.score <= kept.Bound()) break;
      Descend(root, kept);
    }
    return kept.leaves;
  }

 private:
  template <typename Same>
  struct Top {
    float floor;
    float relative_floor;
    int count;
    const Same& same;
    std::vector<Candidate> leaves;  // best first

    // What a block must beat to matter.
    float Bound() const {
      float bound = floor;
      if (!leaves.empty()) bound = std::max(bound, relative_floor * leaves.front().score);
      if (static_cast<int>(leaves.size()) >= count) bound = std::max(bound, leaves.back().score);
      return bound;
    }
    void Offer(const Candidate& leaf) {
      for (Candidate& kept : leaves) {
        if (!same(kept, leaf)) continue;
        if (leaf.score <= kept.score) return;
        kept = leaf;
        Sort();
        return;
      }
      leaves.push_back(leaf);
      Sort();
      if (static_cast<int>(leaves.size()) > count) leaves.pop_back();
      const float relative = relative_floor * leaves.front().score;
      while (!leaves.empty() && leaves.back().score <= relative) leaves.pop_back();
    }
    void Sort() {
      std::sort(leaves.begin(), leaves.end(),
                [](const Candidate& l, const Candidate& r) { return l.score > r.score; });
    }
  };

  float Score(const Candidate& c) const {
    const float* base = pyramid_.Level(c.level) + pyramid_.Offset(c.x, c.y);
    const std::vector<ptrdiff_t>& steps = rotations_[c.yaw_index].steps;
    float sum = 0.0f;
    for (const ptrdiff_t step : steps) sum += base[step];
    return sum / static_cast<float>(steps.size());
  }

  template <typename Kept>
  void Descend(const Candidate& node, Kept& kept) const {
    if (node.level == 0) {
      kept.Offer(node);
      return;
    }
    const RotatedPoints& rot = rotations_[node.yaw_index];
    const int half = 1 << (node.level - 1);
    Candidate children[4];
    int count = 0;
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        Candidate c{node.yaw_index, node.x + dx * half, node.y + dy * half, node.level - 1, 0.0f};
        if (c.x > width_ - 1 - rot.min_x || c.y > height_ - 1 - rot.min_y) continue;
        c.score = Score(c);
        children[count++] = c;
      }
    }
    // Best first (an insertion sort: std::sort on four elements trips GCC 12's -Warray-bounds).
    for (int i = 1; i < count; ++i) {
      for (int j = i; j > 0 && children[j].score > children[j - 1].score; --j) {
        std::swap(children[j], children[j - 1]);
      }
    }
    for (int i = 0; i < count; ++i) {
      if (children[i].score <= kept.Bound()) break;
      Descend(children[i], kept);
    }
  }

  const MaxPyramid& pyramid_;
  const std::vector<RotatedPoints>& rotations_;
  int width_;
  int height_;
};

// The mean field value at `points` moved by `t`, interpolated bilinearly between cell centres
// (a nearest-cell read would score every shift within a cell alike).
double FieldScore(const cv::Mat& field, double res, const std::vector<Point2>& points,
                  const GridTransform& t) {
  const auto at = [&field](int x, int y) {
    return x >= 0 && y >= 0 && x < field.cols && y < field.rows ? field.at<float>(y, x) : 0.0f;
  };
  double sum = 0.0;
  for (const Point2& p : points) {
    const Point2 q = t.Apply(p);
    const double u = q.x() / res - 0.5, v = q.y() / res - 0.5;
    const int x = static_cast<int>(std::floor(u));
    const int y = static_cast<int>(std::floor(v));
    const double fx = u - x, fy = v - y;
    sum += (1.0 - fy) * ((1.0 - fx) * at(x, y) + fx * at(x + 1, y)) +
           fy * ((1.0 - fx) * at(x, y + 1) + fx * at(x + 1, y + 1));
  }
  return sum / static_cast<double>(points.size());
}

// Exhaustive local search around `start` on a yaw x translation lattice.
GridTransform LocalSearch(const cv::Mat& field, double res, const std::vector<Point2>& points,
                          const Point2& pivot, GridTransform start, double yaw_half,
                          double yaw_step, double shift_half, double shift_step) {
  // Rotating about the pivot's image keeps yaw and shift decoupled.
  const Point2 pivot_a = start.Apply(pivot);
  GridTransform best = start;
  double best_score = FieldScore(field, res, points, start);
  const int yaw_steps = static_cast<int>(std::round(yaw_half / yaw_step));
  const int shift_steps = static_cast<int>(std::round(shift_half / shift_step));
  for (int iy = -yaw_steps; iy <= yaw_steps; ++iy) {
    const double yaw = start.yaw + iy * yaw_step;
    const double c = std::cos(yaw), s = std::sin(yaw);
    for (int sy = -shift_steps; sy <= shift_steps; ++sy) {
      for (int sx = -shift_steps; sx <= shift_steps; ++sx) {
        const Point2 target(pivot_a.x() + sx * shift_step, pivot_a.y() + sy * shift_step);
        GridTransform t{yaw, target.x() - (c * pivot.x() - s * pivot.y()),
                        target.y() - (s * pivot.x() + c * pivot.y())};
        const double score = FieldScore(field, res, points, t);
        if (score > best_score) {
          best_score = score;
          best = t;
        }
      }
    }
  }
  return best;
}

Status CheckGrid(const grid::OccupancyGrid& g, const char* name) {
  std::string which(name);
  if (g.empty()) return InvalidArgumentError(which.append(" is empty (no cells)"));
  if (!std::isfinite(g.resolution()) || g.resolution() <= 0.0) {
    return InvalidArgumentError(which.append(" has a resolution that is not a positive number"));
  }
  const Pose2& o = g.origin();
  if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.yaw)) {
    return InvalidArgumentError(which.append(" has a non-finite origin"));
  }
  return Status::Ok();
}

}  // namespace

Status RegistrationOptions::Validate() const {
  if (max_search_cells < 16) return InvalidArgumentError("registration max_search_cells < 16");
  if (!(coarse_yaw_step_deg > 0.0 && coarse_yaw_step_deg <= 10.0)) {
    return InvalidArgumentError("registration coarse_yaw_step_deg must be in (0, 10]");
  }
  if (!(fine_yaw_step_deg > 0.0 && fine_yaw_step_deg <= coarse_yaw_step_deg)) {
    return InvalidArgumentError("registration fine_yaw_step_deg must be in (0, coarse step]");
  }
  if (!(field_sigma_cells > 0.0 && field_sigma_cells <= 10.0)) {
    return InvalidArgumentError("registration field_sigma_cells must be in (0, 10]");
  }
  if (!(free_penalty >= 0.0 && free_penalty <= 10.0)) {
    return InvalidArgumentError("registration free_penalty must be in [0, 10]");
  }
  if (pyramid_levels < 1 || pyramid_levels > 12) {
    return InvalidArgumentError("registration pyramid_levels must be in 1..12");
  }
  if (max_search_points < 10 || max_refine_points < 10) {
    return InvalidArgumentError(
        "registration max_search_points and max_refine_points must be >= 10");
  }
  if (!(distinct_cells > 0.0) || !(distinct_yaw_deg > 0.0)) {
    return InvalidArgumentError("registration distinct_cells and distinct_yaw_deg must be > 0");
  }
  if (!(max_peak_ratio > 0.0 && max_peak_ratio < 1.0)) {
    return InvalidArgumentError("registration max_peak_ratio must be in (0, 1)");
  }
  if (tolerance_cells < 0 || tolerance_cells > 10) {
    return InvalidArgumentError("registration tolerance_cells must be in 0..10");
  }
  if (!(drift_block_m >= 0.5 && drift_block_m <= 100.0)) {
    return InvalidArgumentError("registration drift_block_m must be in [0.5, 100]");
  }
  if (!(max_drift_per_m >= 0.0 && max_drift_per_m <= 0.2) || max_drift_cells < 0 ||
      max_drift_cells > 50) {
    return InvalidArgumentError(
        "registration max_drift_per_m must be in [0, 0.2] and max_drift_cells in 0..50");
  }
  if (candidates < 1 || candidates > 64) {
    return InvalidArgumentError("registration candidates must be in 1..64");
  }
  if (!(verify_contradiction_weight >= 0.0 && verify_contradiction_weight <= 100.0)) {
    return InvalidArgumentError("registration verify_contradiction_weight must be in [0, 100]");
  }
  if (!(symmetry_min_yaw_deg >= 0.0 && symmetry_min_yaw_deg <= 180.0) ||
      !(symmetry_min_agreement >= 0.0 && symmetry_min_agreement <= 1.0) ||
      !(symmetry_max_consistency_drop >= 0.0 && symmetry_max_consistency_drop <= 1.0)) {
    return InvalidArgumentError(
        "registration symmetry_min_yaw_deg must be in [0, 180], symmetry_min_agreement and "
        "symmetry_max_consistency_drop in [0, 1]");
  }
  if (!(symmetry_telling_m >= 0.0 && symmetry_telling_m <= 100.0) ||
      !(symmetry_telling_ratio >= 0.0 && symmetry_telling_ratio <= 1.0)) {
    return InvalidArgumentError(
        "registration symmetry_telling_m must be in [0, 100] and symmetry_telling_ratio in [0, 1]");
  }
  if (min_agreeing_cells < 1) return InvalidArgumentError("registration min_agreeing_cells < 1");
  if (!(min_overlap >= 0.0 && min_overlap <= 1.0)) {
    return InvalidArgumentError("registration min_overlap must be in [0, 1]");
  }
  if (!(min_agreeing_share >= 0.0 && min_agreeing_share <= 1.0)) {
    return InvalidArgumentError("registration min_agreeing_share must be in [0, 1]");
  }
  if (!(max_contradiction >= 0.0 && max_contradiction <= 1.0)) {
    return InvalidArgumentError("registration max_contradiction must be in [0, 1]");
  }
  if (!(min_score >= 0.0 && min_score <= 1.0)) {
    return InvalidArgumentError("registration min_score must be in [0, 1]");
  }
  if (!(min_confidence >= 0.0 && min_confidence <= 1.0)) {
    return InvalidArgumentError("registration min_confidence must be in [0, 1]");
  }
  if (!(thresholds.free >= 0.0 && thresholds.free <= thresholds.occupied &&
        thresholds.occupied <= 1.0)) {
    return InvalidArgumentError("registration thresholds need 0 <= free <= occupied <= 1");
  }
  return Status::Ok();
}

void RegistrationOptions::Describe(OptionsPrinter& out) const {
  out.Add("max_search_cells", max_search_cells);
  out.Add("coarse_yaw_step_deg", coarse_yaw_step_deg);
  out.Add("fine_yaw_step_deg", fine_yaw_step_deg);
  out.Add("field_sigma_cells", field_sigma_cells);
  out.Add("free_penalty", free_penalty);
  out.Add("pyramid_levels", pyramid_levels);
  out.Add("max_search_points", max_search_points);
  out.Add("max_refine_points", max_refine_points);
  out.Add("distinct_cells", distinct_cells);
  out.Add("distinct_yaw_deg", distinct_yaw_deg);
  out.Add("candidates", candidates);
  out.Add("verify_contradiction_weight", verify_contradiction_weight);
  out.Add("max_peak_ratio", max_peak_ratio);
  out.Add("symmetry_min_yaw_deg", symmetry_min_yaw_deg);
  out.Add("symmetry_min_agreement", symmetry_min_agreement);
  out.Add("symmetry_max_consistency_drop", symmetry_max_consistency_drop);
  out.Add("symmetry_telling_m", symmetry_telling_m);
  out.Add("symmetry_telling_ratio", symmetry_telling_ratio);
  out.Add("drift_block_m", drift_block_m);
  out.Add("max_drift_per_m", max_drift_per_m);
  out.Add("max_drift_cells", max_drift_cells);
  out.Add("tolerance_cells", tolerance_cells);
  out.Add("min_agreeing_cells", min_agreeing_cells);
  out.Add("min_agreeing_share", min_agreeing_share);
  out.Add("min_overlap", min_overlap);
  out.Add("max_contradiction", max_contradiction);
  out.Add("min_score", min_score);
  out.Add("min_confidence", min_confidence);
  out.Nested("thresholds", thresholds);
}

StatusOr<Registration> Register(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b,
                                const RegistrationOptions& options) {
  if (Status s = options.Validate(); !s.ok()) return s;
  if (Status s = CheckGrid(a, "map A"); !s.ok()) return s;
  if (Status s = CheckGrid(b, "map B"); !s.ok()) return s;
  const double res = a.resolution();
  if (!grid::SameResolution(a.resolution(), b.resolution())) {
    return InvalidArgumentError(std::string("map A's resolution ")
                                    .append(CleanNumber(a.resolution()))
                                    .append(" m differs from map B's ")
                                    .append(CleanNumber(b.resolution()))
                                    .append(" m; registration does not resample: resample one "
                                            "map first"));
  }
  const grid::StateThresholds& th = options.thresholds;
  if (a.CountStates(th).occupied == 0) return InvalidArgumentError("map A has no occupied cell");
  if (b.CountStates(th).occupied == 0) return InvalidArgumentError("map B has no occupied cell");

  // Coarse grids of at most max_search_cells^2 cells each (by area, so that a long corridor map
  // keeps the resolution its doors need): the search's cost grows with the area.
  const double largest_area = static_cast<double>(std::max(a.cell_count(), b.cell_count()));
  const int factor =
      std::max(1, static_cast<int>(std::ceil(std::sqrt(largest_area) / options.max_search_cells)));
  const double coarse_res = res * factor;
  const CoarseOccupancy coarse_a = Reduce(a, factor, th);
  const CoarseOccupancy coarse_b = Reduce(b, factor, th);
  const cv::Mat coarse_field =
      LikelihoodField(coarse_a.width, coarse_a.height, coarse_a.occupied, coarse_a.free,
                      options.field_sigma_cells, options.free_penalty);

  std::vector<Point2> b_cells;  // coarse cell indices, as doubles
  for (int y = 0; y < coarse_b.height; ++y) {
    for (int x = 0; x < coarse_b.width; ++x) {
      if (coarse_b.occupied[static_cast<size_t>(y) * coarse_b.width + x])
        b_cells.emplace_back(x, y);
    }
  }
  if (static_cast<int>(b_cells.size()) > options.max_search_points) {
    std::vector<Point2> thinned;
    const double stride = static_cast<double>(b_cells.size()) / options.max_search_points;
    for (int i = 0; i < options.max_search_points; ++i) {
      thinned.push_back(b_cells[static_cast<size_t>(i * stride)]);
    }
    b_cells.swap(thinned);
  }
  Point2 centroid(0.0, 0.0);
  for (const Point2& p : b_cells) centroid += p;
  centroid /= static_cast<double>(b_cells.size());

  const int yaw_count =
      std::max(1, static_cast<int>(std::round(360.0 / options.coarse_yaw_step_deg)));
  const double yaw_step = 2.0 * std::numbers::pi / yaw_count;
  std::vector<RotatedPoints> rotations(yaw_count);
  for (int r = 0; r < yaw_count; ++r) {
    RotatedPoints& rot = rotations[r];
    rot.yaw = NormalizeAngle(r * yaw_step);
    const double c = std::cos(rot.yaw), s = std::sin(rot.yaw);
    rot.points.reserve(b_cells.size());
    for (const Point2& p : b_cells) {
      const Point2 d = p - centroid;
      rot.points.push_back({static_cast<int>(std::lround(c * d.x() - s * d.y())),
                            static_cast<int>(std::lround(s * d.x() + c * d.y()))});
    }
    rot.min_x = rot.max_x = rot.points[0].x;
    rot.min_y = rot.max_y = rot.points[0].y;
    for (const CellPoint& p : rot.points) {
      rot.min_x = std::min(rot.min_x, p.x);
      rot.max_x = std::max(rot.max_x, p.x);
      rot.min_y = std::min(rot.min_y, p.y);
      rot.max_y = std::max(rot.max_y, p.y);
    }
  }

  // Placements keep B's cells within one B extent of A's field (some cell overlaps it).
  int extent = 1 << (options.pyramid_levels - 1);
  for (const RotatedPoints& rot : rotations) {
    extent = std::max({extent, rot.max_x - rot.min_x + 1, rot.max_y - rot.min_y + 1});
  }
  const MaxPyramid pyramid(coarse_field, options.pyramid_levels, extent + 1);
  for (RotatedPoints& rot : rotations) {
    rot.steps.reserve(rot.points.size());
    for (const CellPoint& p : rot.points) rot.steps.push_back(pyramid.Step(p.x, p.y));
  }
  const BranchAndBound search(pyramid, rotations, coarse_a.width, coarse_a.height);
  // Clearly different peaks scoring at least kCandidateFloor of the best on the coarse field:
  // at low overlap the coarse field's best peak is often wrong, so the candidates are chosen
  // between by verification below.
  const double distinct_cells2 = options.distinct_cells * options.distinct_cells;
  const int distinct_yaw_steps =
      static_cast<int>(std::ceil(options.distinct_yaw_deg * kDegree / yaw_step));
  const std::vector<Candidate> peaks =
      search.SearchTop(0.02f, static_cast<float>(kCandidateFloor), options.candidates,
                       [&](const Candidate& l, const Candidate& r) {
                         int dyaw = std::abs(l.yaw_index - r.yaw_index);
                         dyaw = std::min(dyaw, yaw_count - dyaw);
                         const double dx = l.x - r.x, dy = l.y - r.y;
                         return dyaw <= distinct_yaw_steps && dx * dx + dy * dy <= distinct_cells2;
                       });
  Registration result;
  if (peaks.empty()) {
    result.why_not = "no placement of B's occupied cells meets A's";
    return result;
  }

  // A coarse hypothesis in grid metres: u_a = R (u_b - centroid) + t in coarse cells, and a
  // coarse cell u's centre is at (u + 0.5) * coarse_res.
  const auto to_grid = [&](const Candidate& c) {
    const double yaw = rotations[c.yaw_index].yaw;
    const double cy = std::cos(yaw), sy = std::sin(yaw);
    const Point2 q(0.5 + centroid.x(), 0.5 + centroid.y());
    return GridTransform{yaw, coarse_res * (c.x + 0.5 - (cy * q.x() - sy * q.y())),
                         coarse_res * (c.y + 0.5 - (sy * q.x() + cy * q.y()))};
  };

  // Refinement at full resolution: a wide likelihood field first, then one a cell wide.
  const CoarseOccupancy full_a = Reduce(a, 1, th);
  const std::vector<Point2> b_points =
      CellCentres(b, grid::CellState::kOccupied, options.max_refine_points, th);
  Point2 pivot(0.0, 0.0);
  for (const Point2& p : b_points) pivot += p;
  pivot /= static_cast<double>(b_points.size());
  const cv::Mat wide_field = LikelihoodField(a.width(), a.height(), full_a.occupied, full_a.free,
                                             std::max(1.0, factor * 0.75), options.free_penalty);
  const cv::Mat fine_field = LikelihoodField(a.width(), a.height(), full_a.occupied, full_a.free,
                                             1.0, options.free_penalty);
  const double coarse_step = options.coarse_yaw_step_deg * kDegree;
  const double mid_shift = std::max(res, coarse_res / 4.0);
  // The wide stage and the first fine one only bring a candidate within half a cell: a quarter
  // of the points does that, and every candidate gets the wide stage.
  std::vector<Point2> b_some_points;
  for (size_t i = 0; i < b_points.size(); i += 4) b_some_points.push_back(b_points[i]);
  const auto refine_wide = [&](const GridTransform& t) {
    return LocalSearch(wide_field, res, b_some_points, pivot, t, coarse_step, 0.25 * coarse_step,
                       coarse_res, mid_shift);
  };
  const auto refine_fine = [&](GridTransform t) {
    t = LocalSearch(fine_field, res, b_some_points, pivot, t, 0.5 * coarse_step, 0.1 * coarse_step,
                    mid_shift, 0.5 * res);
    return LocalSearch(fine_field, res, b_points, pivot, t, 0.1 * coarse_step,
                       options.fine_yaw_step_deg * kDegree, 0.5 * res, 0.25 * res);
  };
  const auto distinct = [&](const GridTransform& l, const GridTransform& r) {
    return (l.Apply(pivot) - r.Apply(pivot)).norm() > options.distinct_cells * coarse_res ||
           std::abs(NormalizeAngle(l.yaw - r.yaw)) > options.distinct_yaw_deg * kDegree;
  };

  // Every candidate is refined and verified at full resolution, and the best verified one wins:
  // the coarse field may blur the door or pillar that tells two places apart, and its score
  // rewards B's walls near A's walls wherever they are, so neither its order nor the fine
  // field's is trusted. Candidates that refine onto the same placement count once.
  const PlacementVerifier verifier(a, b, options);
  struct Verified {
    GridTransform t;
    PlacementVerifier::Verdict verdict;
  };
  const auto by_value = [](const Verified& l, const Verified& r) {
    return l.verdict.value > r.verdict.value;
  };
  // Every candidate gets the wide stage and a first verification; the best kFullyRefined of
  // them the fine stages and the final one, and so does every other that could still be a twin
  // of the best (kRivalShare): on repeated structure the copy that makes the best placement
  // ambiguous may screen fifth or sixth, and a twin left out is a wrong placement accepted.
  std::vector<Verified> screened;
  for (const Candidate& peak : peaks) {
    const GridTransform t = refine_wide(to_grid(peak));
    screened.push_back({t, verifier.Verify(t)});
  }
  std::sort(screened.begin(), screened.end(), by_value);
  const double rival_floor = kRivalShare * std::max(0.0, screened.front().verdict.value);
  size_t finalists = std::min(kFullyRefined, screened.size());
  while (finalists < screened.size() && screened[finalists].verdict.value >= rival_floor &&
         rival_floor > 0.0) {
    ++finalists;
  }
  screened.resize(finalists);
  std::vector<Verified> verified;
  for (const Verified& s : screened) {
    Verified v;
    v.t = refine_fine(s.t);
    // The finalists are judged allowing for drift, so that a drifted map's right placement is
    // not outvoted by walls that land a few cells off far from where the maps meet.
    v.verdict = verifier.VerifyWithDrift(v.t);
    bool merged = false;
    for (Verified& other : verified) {
      if (distinct(other.t, v.t)) continue;
      if (v.verdict.value > other.verdict.value) other = v;
      merged = true;
      break;
    }
    if (!merged) verified.push_back(v);
  }
  std::sort(verified.begin(), verified.end(), by_value);
  const GridTransform grid_a_from_b = verified.front().t;

  // Ambiguity: a clearly different placement that verifies nearly as well (a mirror of a
  // symmetric arena, a corridor, repeated rooms) makes the match ambiguous: a twin.
  // A turned placement that explains a good share of B's walls as consistently as the best one
  // means the structure repeats under a rotation (a point-symmetric arena's mirror, which may
  // even overlap A more than the truth, so its value ratio says nothing): a twin, whatever the
  // values. Shifts at the same yaw are left to the value ratio: sliding along one long wall
  // keeps much of the agreement without being another explanation of B.
  const auto consistency = [](const PlacementVerifier::Verdict& v) {
    return v.agree + v.contradict > 0.0 ? v.agree / (v.agree + v.contradict) : 0.0;
  };
  const PlacementVerifier::Verdict& best = verified.front().verdict;
  const auto turned_like_best = [&](const Verified& other) {
    return std::abs(NormalizeAngle(other.t.yaw - verified.front().t.yaw)) >
               options.symmetry_min_yaw_deg * kDegree &&
           other.verdict.agree >= options.symmetry_min_agreement * best.agree &&
           consistency(other.verdict) >= consistency(best) - options.symmetry_max_consistency_drop;
  };
  // A rival is told apart, and left out (of the ambiguity test and of the score's
  // distinctness), by the cells where the two placements disagree: enough of them favour the
  // best, few the rival (RegistrationOptions::symmetry_telling_m).
  const double telling_cells = options.symmetry_telling_m > 0.0
                                   ? std::ceil(options.symmetry_telling_m / a.resolution())
                                   : std::numeric_limits<double>::infinity();
  const double best_value = best.value;
  double ratio = best_value > 0.0 ? 0.0 : 1.0;
  bool turned_twin = false;
  std::optional<Discrimination> untold;  // the first twin not told apart, for the refusal
  for (size_t k = 1; k < verified.size() && best_value > 0.0; ++k) {
    const double value_ratio = std::clamp(verified[k].verdict.value / best_value, 0.0, 1.0);
    const bool turned = turned_like_best(verified[k]);
    // A rival verifying at kDistinctRatio of the best or less leaves the best fully distinct
    // (the score's distinctness): only closer ones, and turned twins, are judged where they
    // disagree with the best.
    if (!turned && value_ratio <= kDistinctRatio) {
      ratio = std::max(ratio, value_ratio);
      continue;
    }
    const Discrimination d = verifier.Discriminate(verified.front().t, best.drift, verified[k].t,
                                                   verified[k].verdict.drift);
    if (d.for_first >= telling_cells &&
        d.for_second <= options.symmetry_telling_ratio * d.for_first) {
      continue;
    }
    ratio = std::max(ratio, turned ? 1.0 : value_ratio);
    turned_twin = turned_twin || turned;
    if (!untold) untold = d;
  }
  result.peak_ratio = ratio;

  // a_from_b in the map frames: map_a_from_grid_a * grid_a_from_grid_b * grid_b_from_map_b.
  const auto to_map = [&](const GridTransform& t) {
    return Pose2::FromTransform(a.origin().ToTransform() * Pose2{t.tx, t.ty, t.yaw}.ToTransform() *
                                b.origin().ToTransform().inverse());
  };
  result.a_from_b = to_map(grid_a_from_b);
  for (const Verified& v : verified) result.finalists.push_back(to_map(v.t));

  // Verification of the winner, both ways, on every cell.
  const DriftCorrection& drift = verified.front().verdict.drift;
  const Evidence b_in_a = verifier.BInA(grid_a_from_b, drift);
  const Evidence a_in_b = verifier.AInB(grid_a_from_b, drift);
  result.drift = drift.Largest();
  result.agreeing_cells = static_cast<int>(b_in_a.agree);
  result.contradicting_cells = static_cast<int>(b_in_a.contradict + a_in_b.contradict);
  result.overlap = b_in_a.known > 0 ? static_cast<double>(b_in_a.known_shared) / b_in_a.known : 0.0;
  const double agree_both = static_cast<double>(b_in_a.agree + a_in_b.agree);
  const double contradiction =
      agree_both + result.contradicting_cells > 0
          ? result.contradicting_cells / (agree_both + result.contradicting_cells)
          : 1.0;
  const double distinctness = std::min(1.0, (1.0 - result.peak_ratio) / (1.0 - kDistinctRatio));
  result.score = std::clamp((1.0 - contradiction) * distinctness, 0.0, 1.0);
  // What B could show in the overlap: its occupied cells that land on A's known cells.
  const int needed_agreeing =
      std::max(options.min_agreeing_cells,
               static_cast<int>(std::ceil(options.min_agreeing_share * b_in_a.occupied_shared)));
  const bool drift_tolerant = options.max_drift_per_m > 0.0 && options.max_drift_cells > 0;
  result.confidence =
      (drift_tolerant ? ConfidenceCalibration::DriftTolerant() : ConfidenceCalibration::Default())
          .Probability(result.score);

  if (result.overlap < options.min_overlap) {
    result.why_not = std::string("too little shared structure: ")
                         .append(Num(100.0 * result.overlap))
                         .append(" % of B's known cells land on A's known cells (at least ")
                         .append(Num(100.0 * options.min_overlap))
                         .append(" % needed)");
  } else if (result.agreeing_cells < needed_agreeing) {
    result.why_not = std::string("too little shared structure: ")
                         .append(std::to_string(result.agreeing_cells))
                         .append(" of B's ")
                         .append(std::to_string(b_in_a.occupied_shared))
                         .append(" occupied cells on A's known cells agree with A (at least ")
                         .append(std::to_string(needed_agreeing))
                         .append(" needed)");
  } else if (contradiction > options.max_contradiction) {
    result.why_not = std::string("the best placement contradicts the maps: ")
                         .append(Num(100.0 * contradiction))
                         .append(" % of the occupied cells in the overlap land on free cells");
  } else if (turned_twin) {
    result.why_not =
        std::string(
            "ambiguous: a placement turned against the best explains B's walls about as "
            "consistently (the structure repeats under a rotation)")
            .append(TellingApart(untold, a.resolution(), options));
  } else if (result.peak_ratio >= options.max_peak_ratio) {
    result.why_not = std::string("ambiguous: a clearly different placement verifies ")
                         .append(Num(100.0 * result.peak_ratio))
                         .append(" % of the best (symmetric or repeated structure)")
                         .append(TellingApart(untold, a.resolution(), options));
  } else if (result.score < options.min_score) {
    result.why_not = std::string("score ")
                         .append(Num(result.score))
                         .append(" is below ")
                         .append(Num(options.min_score));
  } else if (result.confidence < options.min_confidence) {
    result.verified = true;
    // Two decimals, as confidences are quoted, unless that would misquote the bar (0.999 as
    // 1.00) or print the confidence as high as the bar.
    const double bar_2 = std::round(100.0 * options.min_confidence) / 100.0;
    const int digits = std::abs(bar_2 - options.min_confidence) < 1e-9 &&
                               Fixed(result.confidence, 2) != Fixed(options.min_confidence, 2)
                           ? 2
                           : 4;
    result.why_not = std::string("confidence ")
                         .append(Fixed(result.confidence, digits))
                         .append(" below the placement bar ")
                         .append(Fixed(options.min_confidence, digits));
  } else {
    result.verified = true;
    result.found = true;
  }
  return result;
}

}  // namespace fleetmap::registration
