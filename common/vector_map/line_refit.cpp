#include "common/vector_map/line_refit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <utility>

#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {
namespace {

// A segment's fit needs this many cells.
constexpr double kMinFitCells = 3.0;
// A fitted direction is used only where the cells are clearly elongated along it (smaller over
// larger second moment below this) and it turns the segment by less than 30 degrees; otherwise
// the segment keeps its direction and only its offset is fitted.
constexpr double kMaxMomentRatio = 0.25;
constexpr double kMinTurnCosine = 0.866;
// Fitted lines nearer to parallel than 15 degrees are not intersected (the crossing would be
// ill-conditioned); the vertex goes to the mean of its projections onto them.
constexpr double kMinCrossingSine = 0.26;

// The occupied cells a segment stands for: moments about the segment's first vertex, and their
// extent along the segment (from the first vertex).
struct Moments {
  double n = 0.0;
  double sx = 0.0;
  double sy = 0.0;
  double sxx = 0.0;
  double sxy = 0.0;
  double syy = 0.0;
  double min_along = std::numeric_limits<double>::infinity();
  double max_along = -std::numeric_limits<double>::infinity();
};

// A P point of the rectangle near a segment: raster index and cell.
struct NearPoint {
  int index;
  int x;
  int y;
};

// A cell beyond the minimum radius of a candidate: squared distance, match value, raster index.
struct Ranked {
  double d2;
  int value;
  int index;
};

struct Line {
  Point2 point = Point2::Zero();
  Point2 dir = Point2::Zero();  // unit, oriented like its segment
  bool valid = false;
};

double Cross(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

Point2 Project(const Line& line, const Point2& p) {
  return line.point + line.dir * (p - line.point).dot(line.dir);
}

// The principal axis of a 2 x 2 second-moment matrix, and whether the cells are elongated along
// it (smaller over larger eigenvalue below kMaxMomentRatio).
bool PrincipalAxis(double cxx, double cxy, double cyy, Point2& axis) {
  const double half_trace = 0.5 * (cxx + cyy);
  const double root = std::hypot(0.5 * (cxx - cyy), cxy);
  const double large = half_trace + root;
  const double small = half_trace - root;
  if (!(large > 0.0)) return false;
  const double angle = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  axis = Point2(std::cos(angle), std::sin(angle));
  return small <= kMaxMomentRatio * large;
}

// Per-cell scratch of the raster's size, kept per thread between calls (no page faults per call),
// one 16-byte record per cell so that a band visit touches one cache line per cell; every cell
// written is listed in `touched` and reset after the run.
struct ScratchCell {
  static constexpr uint8_t kSeen = 1;     // listed in `touched`
  static constexpr uint8_t kInRect = 2;   // inside the rectangle (set when first listed)
  static constexpr uint8_t kOwned = 4;    // `fit` holds the nearest segment (fitting phase)
  static constexpr uint8_t kCounted = 8;  // in `paint` for the polyline being counted

  union {
    double distance = -1.0;  // evaluation: squared distance to the candidate; -1: none
    struct {
      float distance;  // squared
      int segment;
    } fit;  // fitting phase: the nearest segment within epsilon
  };
  uint16_t paint = 0;  // polylines painting the cell
  uint16_t cover = 0;  // segments within epsilon of the cell (P points of the rectangle)
  uint8_t flags = 0;
};

struct Scratch {
  std::vector<ScratchCell> cells;
  std::vector<int> touched;

  void Fit(size_t size) {
    if (cells.size() < size) cells.resize(size);
    touched.clear();
  }
  ScratchCell& Touch(int i, int x, int y, const CellRect& rect) {
    ScratchCell& cell = cells[i];
    if ((cell.flags & ScratchCell::kSeen) == 0) {
      cell.flags = ScratchCell::kSeen | (rect.Contains(x, y) ? ScratchCell::kInRect : 0);
      touched.push_back(i);
    }
    return cell;
  }
  void Restore() {
    for (const int i : touched) cells[i] = ScratchCell{};
    touched.clear();
  }
};

Scratch& ThreadScratch() {
  thread_local Scratch scratch;
  return scratch;
}

class RefitRun {
 public:
  RefitRun(const CellRaster& raster, const LineRefitOptions& options,
           std::vector<CellPolyline>& polylines, std::vector<double>& half_widths)
      : raster_(raster),
        options_(options),
        polylines_(polylines),
        half_widths_(half_widths),
        eps2_(ToleratedSquare(options.epsilon)),
        s_(ThreadScratch()) {}

  LineRefitStats Run() {
    s_.Fit(raster_.size());
    Index();
    MarkShared();
    PaintCoverAndOwn();
    FitLines();
    LineRefitStats stats;
    std::vector<Point2> candidate;
    std::vector<uint8_t> moved;
    for (size_t k = 0; k < polylines_.size(); ++k) {
      if (!Propose(k, candidate, moved)) continue;
      const int count = Evaluate(k, candidate, moved);
      if (count > 0) {
        ++stats.polylines_moved;
        stats.vertices_moved += count;
      }
    }
    s_.Restore();
    return stats;
  }

 private:
  // Segment j of a polyline of n points joins points j and (j + 1) % n; a point obstacle is one
  // zero-length segment.
  static int SegmentCount(const CellPolyline& polyline) {
    const int n = static_cast<int>(polyline.points.size());
    if (n <= 1) return n;
    return polyline.closed && n >= 3 ? n : n - 1;
  }
  // The far end of segment j.
  static const Point2& End(const std::vector<Point2>& pts, int j) {
    return pts[pts.size() == 1 ? 0 : (static_cast<size_t>(j) + 1) % pts.size()];
  }

  double PaintRadius(double half_width) const {
    const double h =
        options_.emitted_half_width ? options_.emitted_half_width(half_width) : half_width;
    return std::max(h, options_.min_radius);
  }
  Point2 Snap(const Point2& p) const { return options_.snap ? options_.snap(p) : p; }
  bool OwnedP(int i) const { return raster_.Has(i, CellRaster::kOwned); }

  // Calls f(raster index, x, y, squared distance) for the cells of the raster within `radius` (up
  // to ToleratedSquare) of segment [a, b].
  template <typename F>
  void Visit(const Point2& a, const Point2& b, double radius, F&& f) const {
    const double r2 = ToleratedSquare(radius);
    ForEachCellNearSegmentIn(raster_.window(), a, b, radius, [&](int x, int y) {
      const double d2 = PointSegmentDistanceSquared(Point2(x, y), a, b);
      if (d2 <= r2) f(raster_.Index(x, y), x, y, d2);
    });
  }

  void Index() {
    segment_begin_.assign(polylines_.size() + 1, 0);
    vertex_begin_.assign(polylines_.size() + 1, 0);
    for (size_t k = 0; k < polylines_.size(); ++k) {
      segment_begin_[k + 1] = segment_begin_[k] + SegmentCount(polylines_[k]);
      vertex_begin_[k + 1] = vertex_begin_[k] + static_cast<int>(polylines_[k].points.size());
    }
  }

  // Vertices that may not move: border nodes, point obstacles, and any vertex stored more than
  // once (a junction shared by polylines, a polyline touching itself).
  void MarkShared() {
    fixed_.assign(static_cast<size_t>(vertex_begin_.back()), 0);
    std::vector<std::tuple<double, double, int>> all;
    all.reserve(fixed_.size());
    for (size_t k = 0; k < polylines_.size(); ++k) {
      const CellPolyline& polyline = polylines_[k];
      const int base = vertex_begin_[k];
      const int n = static_cast<int>(polyline.points.size());
      for (int i = 0; i < n; ++i) {
        all.emplace_back(polyline.points[i].x(), polyline.points[i].y(), base + i);
      }
      if (n == 1) fixed_[base] = 1;
      if (n >= 2 && !polyline.closed) {
        if (polyline.start_on_border) fixed_[base] = 1;
        if (polyline.end_on_border) fixed_[base + n - 1] = 1;
      }
    }
    std::sort(all.begin(), all.end());
    for (size_t i = 0; i + 1 < all.size(); ++i) {
      if (std::get<0>(all[i]) == std::get<0>(all[i + 1]) &&
          std::get<1>(all[i]) == std::get<1>(all[i + 1])) {
        fixed_[std::get<2>(all[i])] = 1;
        fixed_[std::get<2>(all[i + 1])] = 1;
      }
    }
  }

  // Paint counts (per polyline) at each polyline's radius and the cells each paints, coverage
  // counts (per segment) of the rectangle's P points, and the nearest segment of every cell within
  // epsilon.
  void PaintCoverAndOwn() {
    painted_begin_.assign(polylines_.size() + 1, 0);
    painted_.clear();
    near_begin_.assign(static_cast<size_t>(segment_begin_.back()) + 1, 0);
    near_.clear();
    // The cell loop reads only locals: its byte stores may alias anything read through a
    // reference or a member, which would then be reloaded for every cell.
    const CellRect window = raster_.window();
    const CellRect rect = raster_.rect();
    const uint8_t* const flags = raster_.data();
    ScratchCell* const cells = s_.cells.data();
    const double eps2 = eps2_;
    for (size_t k = 0; k < polylines_.size(); ++k) {
      const auto& pts = polylines_[k].points;
      const double r = PaintRadius(half_widths_[k]);
      const double r2 = ToleratedSquare(r);
      for (int j = 0; j < SegmentCount(polylines_[k]); ++j) {
        const int segment = segment_begin_[k] + j;
        const Point2 a = pts[j];
        const Point2 b = End(pts, j);
        const double radius = std::max(r, options_.epsilon);
        const double radius2 = ToleratedSquare(radius);
        ForEachCellNearSegmentIn(window, a, b, radius, [&, flags, cells](int x, int y) {
          const double d2 = PointSegmentDistanceSquared(Point2(x, y), a, b);
          if (d2 > radius2) return;
          const int i = (y - window.y0) * window.width + (x - window.x0);  // raster_.Index(x, y)
          ScratchCell& cell = cells[i];
          if ((cell.flags & ScratchCell::kSeen) == 0) {  // s_.Touch(i, x, y, rect)
            cell.flags = ScratchCell::kSeen | (rect.Contains(x, y) ? ScratchCell::kInRect : 0);
            s_.touched.push_back(i);
          }
          if (d2 <= r2 && (cell.flags & ScratchCell::kCounted) == 0) {
            cell.flags |= ScratchCell::kCounted;
            ++cell.paint;
            painted_.push_back(i);
          }
          if (d2 > eps2) return;
          if ((flags[i] & CellRaster::kOwned) != 0) {
            ++cell.cover;
            near_.push_back({i, x, y});
          }
          if ((cell.flags & ScratchCell::kOwned) == 0 ||
              static_cast<float>(d2) < cell.fit.distance) {
            cell.flags |= ScratchCell::kOwned;
            cell.fit = {static_cast<float>(d2), segment};
          }
        });
        near_begin_[segment + 1] = static_cast<int>(near_.size());
      }
      painted_begin_[k + 1] = static_cast<int>(painted_.size());
      for (int m = painted_begin_[k]; m < painted_begin_[k + 1]; ++m) {
        s_.cells[painted_[m]].flags &= static_cast<uint8_t>(~ScratchCell::kCounted);
      }
    }
  }

  // One line per segment through the occupied cells it stands for (see the header).
  void FitLines() {
    std::vector<Moments> moments(static_cast<size_t>(segment_begin_.back()));
    std::vector<Point2> first(moments.size());
    std::vector<Point2> unit(moments.size(), Point2::Zero());
    std::vector<double> length(moments.size(), 0.0);
    for (size_t k = 0; k < polylines_.size(); ++k) {
      const auto& pts = polylines_[k].points;
      for (int j = 0; j < SegmentCount(polylines_[k]); ++j) {
        const int segment = segment_begin_[k] + j;
        first[segment] = pts[j];
        length[segment] = (End(pts, j) - pts[j]).norm();
        if (length[segment] > kDistanceTolerance) {
          unit[segment] = (End(pts, j) - pts[j]) / length[segment];
        }
      }
    }
    for (const int i : s_.touched) {
      ScratchCell& cell = s_.cells[i];
      if ((cell.flags & ScratchCell::kOwned) == 0) continue;
      const int segment = cell.fit.segment;
      cell.distance = -1.0;  // free for the evaluation phase
      if (!raster_.Has(i, CellRaster::kOccupied)) continue;
      Moments& m = moments[segment];
      const double x = raster_.X(i) - first[segment].x();
      const double y = raster_.Y(i) - first[segment].y();
      m.n += 1.0;
      m.sx += x;
      m.sy += y;
      m.sxx += x * x;
      m.sxy += x * y;
      m.syy += y * y;
      const double along = x * unit[segment].x() + y * unit[segment].y();
      m.min_along = std::min(m.min_along, along);
      m.max_along = std::max(m.max_along, along);
    }
    lines_.assign(moments.size(), Line{});
    beyond_.assign(moments.size(), {0.0, 0.0});
    for (size_t k = 0; k < polylines_.size(); ++k) {
      const CellPolyline& polyline = polylines_[k];
      const int n = static_cast<int>(polyline.points.size());
      if (n < 2) continue;
      for (int j = 0; j < SegmentCount(polyline); ++j) {
        const int segment = segment_begin_[k] + j;
        const Moments& m = moments[segment];
        if (m.n < kMinFitCells || length[segment] <= kDistanceTolerance) continue;
        const bool fixed_a = fixed_[vertex_begin_[k] + j] != 0;
        const bool fixed_b = fixed_[vertex_begin_[k] + (j + 1) % n] != 0;
        if (fixed_a && fixed_b) continue;
        Line& line = lines_[segment];
        const Point2& u = unit[segment];
        Point2 axis;
        if (fixed_a || fixed_b) {
          // Through the fixed end: moments about it.
          const Point2 f = (fixed_a ? Point2::Zero() : Point2(length[segment] * u));
          const double cxx = m.sxx - 2.0 * f.x() * m.sx + m.n * f.x() * f.x();
          const double cxy = m.sxy - f.x() * m.sy - f.y() * m.sx + m.n * f.x() * f.y();
          const double cyy = m.syy - 2.0 * f.y() * m.sy + m.n * f.y() * f.y();
          if (!PrincipalAxis(cxx, cxy, cyy, axis) || std::abs(axis.dot(u)) < kMinTurnCosine) {
            continue;  // a line through the fixed end in the old direction is the old line
          }
          line.point = first[segment] + f;
        } else {
          const double cx = m.sx / m.n;
          const double cy = m.sy / m.n;
          const bool elongated = PrincipalAxis(m.sxx / m.n - cx * cx, m.sxy / m.n - cx * cy,
                                               m.syy / m.n - cy * cy, axis);
          if (!elongated || std::abs(axis.dot(u)) < kMinTurnCosine) axis = u;
          line.point = first[segment] + Point2(cx, cy);
        }
        line.dir = axis.dot(u) < 0.0 ? Point2(-axis) : axis;
        line.valid = true;
        // How far the cells reach beyond each end, along the segment.
        beyond_[segment] = {std::max(0.0, -m.min_along),
                            std::max(0.0, m.max_along - length[segment])};
      }
    }
  }

  // The fitted position of every movable vertex of polyline k, snapped; false if none moves by
  // min_move or more.
  bool Propose(size_t k, std::vector<Point2>& candidate, std::vector<uint8_t>& moved) const {
    const CellPolyline& polyline = polylines_[k];
    const auto& pts = polyline.points;
    const int n = static_cast<int>(pts.size());
    if (n < 2) return false;
    candidate = pts;
    moved.assign(static_cast<size_t>(n), 0);
    bool any = false;
    for (int i = 0; i < n; ++i) {
      if (fixed_[vertex_begin_[k] + i]) continue;
      const bool has_prev = i > 0 || polyline.closed;
      const bool has_next = i < n - 1 || polyline.closed;
      const int prev = segment_begin_[k] + (i + n - 1) % n;
      const int next = segment_begin_[k] + i;
      const Line* before = has_prev && lines_[prev].valid ? &lines_[prev] : nullptr;
      const Line* after = has_next && lines_[next].valid ? &lines_[next] : nullptr;
      const Point2& v = pts[i];
      Point2 q = v;
      if (before != nullptr && after != nullptr) {
        const double sine = Cross(before->dir, after->dir);
        if (std::abs(sine) >= kMinCrossingSine) {
          const double t = Cross(after->point - before->point, after->dir) / sine;
          q = before->point + t * before->dir;
        }
        if (std::abs(sine) < kMinCrossingSine || (q - v).norm() > options_.max_move) {
          q = 0.5 * (Project(*before, v) + Project(*after, v));
        }
      } else if (before != nullptr || after != nullptr) {
        const Line& line = before != nullptr ? *before : *after;
        q = Project(line, v);
        if ((q - v).norm() > options_.max_move) continue;
        // A free end goes out to the farthest of its segment's cells.
        if (!has_next) q += line.dir * beyond_[prev].second;
        if (!has_prev) q -= line.dir * beyond_[next].first;
      } else {
        continue;
      }
      // An end may also go out along its line, by at most epsilon (the cells it stands for).
      const double reach = options_.max_move + (has_prev && has_next ? 0.0 : options_.epsilon);
      if (!((q - v).norm() <= reach)) continue;
      if (options_.position_step > 0.0) {
        const double step = options_.position_step;
        q = Point2(std::round(q.x() / step) * step, std::round(q.y() / step) * step);
      }
      q = Snap(q);
      if ((q - v).norm() < options_.min_move) continue;
      candidate[i] = q;
      moved[i] = 1;
      any = true;
    }
    return any;
  }

  // Whether P point p (of the rectangle, near old segment j) is within epsilon of some segment
  // once the candidate replaces the changed segments: first the candidate's neighbours of segment
  // j, else exactly from the coverage counts.
  bool CoveredAfter(int i, const Point2& p, int j, const std::vector<Point2>& pts,
                    const std::vector<Point2>& candidate) const {
    const int n = static_cast<int>(pts.size());
    const int segments = static_cast<int>(changed_flag_.size());
    for (const int step : {-1, 1}) {
      int s = j + step;
      if (s < 0 || s >= segments) {
        if (!closed_) continue;
        s = (s + segments) % segments;
      }
      if (PointSegmentDistanceSquared(p, candidate[s], candidate[(s + 1) % n]) <= eps2_) {
        return true;
      }
    }
    int count = s_.cells[i].cover;
    for (const int c : changed_) {
      if (PointSegmentDistanceSquared(p, pts[c], pts[(c + 1) % n]) <= eps2_) --count;
      if (PointSegmentDistanceSquared(p, candidate[c], candidate[(c + 1) % n]) <= eps2_) ++count;
    }
    return count > 0;
  }

  // A changed segment: one visit of the candidate's band records its distances (for the score),
  // the continuity intervals of the new segment and the P points it covers; the P points the old
  // segment covered (listed by PaintCoverAndOwn) are checked to stay covered. False if the new
  // segment is not continuous; P points that would be left uncovered go to uncovered_.
  bool ExamineChanged(int segment, int j, const std::vector<Point2>& pts,
                      const std::vector<Point2>& candidate, double r_max) {
    const int n = static_cast<int>(pts.size());
    const Point2& a = candidate[j];
    const Point2& b = candidate[(j + 1) % n];
    const double length = (b - a).norm();
    const double ux = length > 0.0 ? (b.x() - a.x()) / length : 0.0;
    const double uy = length > 0.0 ? (b.y() - a.y()) / length : 0.0;
    const double r_max2 = ToleratedSquare(r_max);
    intervals_.clear();
    Visit(a, b, std::max(r_max, options_.epsilon), [&](int i, int x, int y, double d2) {
      if (d2 <= r_max2) RecordDistance(i, x, y, d2);
      if (d2 > eps2_ || !raster_.Has(i, CellRaster::kDelimitation)) return;
      if (OwnedP(i)) new_cover_.push_back(i);
      // The interval of the new segment inside p's epsilon-disc, as SegmentContinuousIf computes
      // it.
      const double wx = x - a.x();
      const double wy = y - a.y();
      const double along = wx * ux + wy * uy;
      const double half2 = eps2_ - (wx * wx + wy * wy - along * along);
      if (half2 < 0.0) return;
      const double half = std::sqrt(half2);
      if (!(along + half < 0.0 || along - half > length)) {
        intervals_.emplace_back(along - half, along + half);
      }
    });
    for (int m = near_begin_[segment]; m < near_begin_[segment + 1]; ++m) {
      const NearPoint& near = near_[m];
      old_cover_.push_back(near.index);
      const Point2 p(near.x, near.y);
      if (PointSegmentDistanceSquared(p, a, b) > eps2_ &&
          !CoveredAfter(near.index, p, j, pts, candidate)) {
        uncovered_.push_back(near.index);
      }
    }
    if (length < kDistanceTolerance) {
      return SegmentContinuousIf(a, b, options_.epsilon,
                                 [&](int x, int y) { return raster_.IsDelimitation(x, y); });
    }
    return IntervalsCover(intervals_, length);
  }

  void RecordDistance(int i, int x, int y, double d2) {
    ScratchCell& cell = s_.Touch(i, x, y, raster_.rect());
    if (cell.distance < 0.0) {
      cell.distance = d2;
      new_cells_.push_back(i);
    } else {
      cell.distance = std::min(cell.distance, d2);
    }
  }

  void ForgetDistances() {
    for (const int i : new_cells_) s_.cells[i].distance = -1.0;
    new_cells_.clear();
  }

  // Drops moves until every changed segment is continuous and every P point of the rectangle
  // near an old segment is still covered, meanwhile recording the candidate's distances (up to
  // r_max) in new_cells_ and the P points leaving and joining the coverage counts in old_cover_
  // and new_cover_. Returns the number of vertices still moved.
  int KeepValidMoves(size_t k, std::vector<Point2>& candidate, std::vector<uint8_t>& moved,
                     double r_max) {
    const CellPolyline& polyline = polylines_[k];
    const auto& pts = polyline.points;
    const int n = static_cast<int>(pts.size());
    const int segments = SegmentCount(polyline);
    closed_ = polyline.closed;
    auto revert = [&](int j) {
      for (const int i : {j, (j + 1) % n}) {
        candidate[i] = pts[i];
        moved[i] = 0;
      }
    };
    while (true) {
      changed_.clear();
      changed_flag_.assign(static_cast<size_t>(segments), 0);
      for (int j = 0; j < segments; ++j) {
        if (moved[j] || moved[(j + 1) % n]) {
          changed_.push_back(j);
          changed_flag_[j] = 1;
        }
      }
      if (changed_.empty()) return 0;
      ForgetDistances();
      old_cover_.clear();
      new_cover_.clear();
      uncovered_.clear();
      discontinuous_.clear();
      for (int j = 0; j < segments; ++j) {
        const int j1 = (j + 1) % n;
        if (!changed_flag_[j]) {
          Visit(candidate[j], candidate[j1], r_max,
                [&](int i, int x, int y, double d2) { RecordDistance(i, x, y, d2); });
        } else if (!ExamineChanged(segment_begin_[k] + j, j, pts, candidate, r_max)) {
          discontinuous_.push_back(j);
        }
      }
      if (discontinuous_.empty() && uncovered_.empty()) {
        int count = 0;
        for (int i = 0; i < n; ++i) count += moved[i];
        return count;
      }
      for (const int j : discontinuous_) revert(j);
      for (const int i : uncovered_) {
        const Point2 p(raster_.X(i), raster_.Y(i));
        for (const int j : changed_) {
          if (PointSegmentDistanceSquared(p, pts[j], pts[(j + 1) % n]) <= eps2_) revert(j);
        }
      }
    }
  }

  // The match value of painting cell i, given what the other polylines paint.
  int Value(int i) const {
    if (s_.cells[i].paint > 0) return 0;
    if (!raster_.Has(i, CellRaster::kOccupied)) return -1;
    return (s_.cells[i].flags & ScratchCell::kInRect) != 0 ? 1 : 0;
  }

  // Keeps the candidate (with its best half width) if it passes the constraints and raises the
  // match; returns the number of vertices moved (0: the old polyline stays).
  int Evaluate(size_t k, std::vector<Point2>& candidate, std::vector<uint8_t>& moved) {
    // The candidate's distances out to the largest radius it could get.
    const double r_max = std::max(PaintRadius(options_.epsilon), options_.min_radius);
    const int count = KeepValidMoves(k, candidate, moved, r_max);
    if (count == 0) {
      ForgetDistances();
      return 0;
    }
    CellPolyline& polyline = polylines_[k];
    // The old band leaves the paint counts; what is left is the other polylines' paint.
    int old_score = 0;
    for (int m = painted_begin_[k]; m < painted_begin_[k + 1]; ++m) --s_.cells[painted_[m]].paint;
    for (int m = painted_begin_[k]; m < painted_begin_[k + 1]; ++m) old_score += Value(painted_[m]);
    // Cells within the minimum radius are painted whatever the half width; the others are ranked
    // by distance.
    const double min2 = ToleratedSquare(PaintRadius(0.0));
    int base_score = 0;
    ranked_.clear();
    for (const int i : new_cells_) {
      const double d2 = s_.cells[i].distance;
      if (d2 <= min2) {
        base_score += Value(i);
      } else {
        ranked_.push_back({d2, Value(i), i});
      }
    }
    std::sort(ranked_.begin(), ranked_.end(),
              [](const Ranked& a, const Ranked& b) { return a.d2 < b.d2; });
    // Half widths to try: 0 (the minimum radius) and the distance of each ranked cell (capped at
    // epsilon); each paints a prefix of `ranked_` (the radius a reader sees grows with it).
    int best_score = base_score;
    double best_half_width = 0.0;
    size_t best_painted = 0;
    size_t painted = 0;
    int prefix = base_score;
    // The cells come sorted by distance, so equal half widths (ties, and every cell beyond
    // epsilon) are adjacent: each radius is computed once.
    double r2_half_width = -1.0;
    double r2 = 0.0;
    for (const Ranked& cell : ranked_) {
      const double half_width = std::min(options_.epsilon, std::sqrt(cell.d2));
      if (half_width != r2_half_width) {
        r2_half_width = half_width;
        r2 = ToleratedSquare(PaintRadius(half_width));
      }
      while (painted < ranked_.size() && ranked_[painted].d2 <= r2) {
        prefix += ranked_[painted].value;
        ++painted;
      }
      if (prefix > best_score) {
        best_score = prefix;
        best_half_width = half_width;
        best_painted = painted;
      }
    }
    const bool keep = best_score > old_score;
    if (!keep) {
      for (int m = painted_begin_[k]; m < painted_begin_[k + 1]; ++m) ++s_.cells[painted_[m]].paint;
    } else {
      // Its band joins the paint counts (it is never removed again); its changed segments replace
      // the old ones in the coverage counts.
      for (const int i : new_cells_) ++s_.cells[i].paint;  // then off again for those not painted
      for (size_t m = best_painted; m < ranked_.size(); ++m) --s_.cells[ranked_[m].index].paint;
      for (const int i : old_cover_) --s_.cells[i].cover;
      for (const int i : new_cover_) ++s_.cells[i].cover;
      polyline.points = candidate;
      half_widths_[k] = best_half_width;
    }
    ForgetDistances();
    return keep ? count : 0;
  }

  const CellRaster& raster_;
  const LineRefitOptions& options_;
  std::vector<CellPolyline>& polylines_;
  std::vector<double>& half_widths_;
  double eps2_;
  Scratch& s_;
  std::vector<int> segment_begin_;
  std::vector<int> vertex_begin_;
  std::vector<uint8_t> fixed_;
  std::vector<Line> lines_;
  std::vector<std::pair<double, double>> beyond_;  // per segment: before its start, past its end
  std::vector<int> painted_begin_;                 // per polyline, into painted_
  std::vector<int> painted_;     // the cells each polyline paints, as first counted
  std::vector<int> near_begin_;  // per segment, into near_
  std::vector<NearPoint> near_;  // the P points of the rectangle within epsilon of each
  bool closed_ = false;          // the polyline being evaluated is closed
  std::vector<int> changed_;
  std::vector<int> discontinuous_;
  std::vector<std::pair<double, double>> intervals_;
  std::vector<uint8_t> changed_flag_;
  std::vector<int> uncovered_;
  std::vector<int> old_cover_;
  std::vector<int> new_cover_;
  std::vector<int> new_cells_;
  std::vector<Ranked> ranked_;
};

}  // namespace

LineRefitStats RefitLines(const CellRaster& raster, const LineRefitOptions& options,
                          std::vector<CellPolyline>& polylines, std::vector<double>& half_widths) {
  return RefitRun(raster, options, polylines, half_widths).Run();
}

}  // namespace fleetmap::vector_map
