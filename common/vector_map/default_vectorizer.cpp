#include "common/vector_map/default_vectorizer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "common/vector_map/border_nodes.hpp"
#include "common/vector_map/chain_simplifier.hpp"
#include "common/vector_map/chain_tracer.hpp"
#include "common/vector_map/half_width.hpp"
#include "common/vector_map/segment_geometry.hpp"
#include "common/vector_map/skeleton.hpp"
#include "common/vector_map/speck_cover.hpp"

namespace fleetmap::vector_map {
namespace {

// A chain ready for simplification: its points (skeleton pixels, plus border nodes at the ends),
// and the P points attached to each point (CSR buckets, by global position).
struct Chain {
  std::vector<Point2> points;
  std::array<bool, 2> on_border = {false, false};
  bool ring = false;
  int base = 0;  // global position of points[0]
};

constexpr double kMinHalfWidth = 0.5;  // cells: the Rasterizer paints at least this far

// Chains kept per thread between tiles, with their point buffers (a tile has hundreds of chains).
std::vector<Chain>& ThreadChains() {
  thread_local std::vector<Chain> chains;
  return chains;
}

// A zeroed per-thread int image, reused across calls (callers restore the zeros).
std::vector<int>& ZeroedSlots(size_t size) {
  thread_local std::vector<int> slots;
  if (slots.size() < size) slots.resize(size, 0);
  return slots;
}

class TileRun {
 public:
  TileRun(CellRaster& raster, const grid::OccupancyGrid& grid,
          const grid::StateThresholds& thresholds, double epsilon)
      : raster_(raster),
        nodes_(raster, grid, thresholds),
        eps_(epsilon),
        eps2_(ToleratedSquare(epsilon)),
        chains_(ThreadChains()) {}

  std::vector<CellPolyline> Run() {
    const std::vector<int> skeleton = ThinToSkeleton(raster_, eps_);
    pixel_chains_ = TraceChains(raster_, skeleton);
    BuildChains();
    Attach();
    std::vector<CellPolyline> polylines;
    for (size_t c = 0; c < chain_count_; ++c) {
      const size_t first = polylines.size();
      Simplify(c, polylines);
      ChooseCover(c, first, polylines);
    }
    polylines = MergeAtSharedEnds(std::move(polylines));
    CoverRemaining(raster_, eps_, polylines);
    return polylines;
  }

 private:
  Point2 CellPoint(int index) const { return Point2(raster_.X(index), raster_.Y(index)); }
  bool Continuous(const Point2& a, const Point2& b) const {
    return SegmentContinuousIf(a, b, eps_,
                               [&](int x, int y) { return raster_.IsDelimitation(x, y); });
  }

  // Points of each chain; an end pixel of degree <= 1 next to an anchor across the tile border is
  // extended to the border node. One-pixel chains without a node are left to the cover stage.
  // The first chain_count_ of chains_ are this tile's (the others keep their buffers for later).
  void BuildChains() {
    chain_count_ = 0;
    chain_pixels_.clear();
    int position = 0;
    for (const PixelChain& pixel_chain : pixel_chains_) {
      const auto& pixels = pixel_chain.pixels;
      if (chain_count_ == chains_.size()) chains_.emplace_back();
      Chain& chain = chains_[chain_count_];
      chain.points.clear();
      chain.on_border = {false, false};
      chain.ring = pixel_chain.ring();
      chain.points.reserve(pixels.size() + 2);  // and the border nodes
      for (const int index : pixels) chain.points.push_back(CellPoint(index));
      if (!chain.ring) {
        for (int side = 0; side < 2; ++side) {
          const int end = side == 0 ? pixels.front() : pixels.back();
          if (SkeletonDegree(raster_, end) > 1) continue;
          if (pixels.size() == 1 && side == 1 && chain.on_border[0]) continue;
          const int next =
              pixels.size() >= 2 ? (side == 0 ? pixels[1] : pixels[pixels.size() - 2]) : -1;
          const auto node = nodes_.For(end, next);
          if (!node || !Continuous(CellPoint(end), *node)) continue;
          if (side == 0) {
            chain.points.insert(chain.points.begin(), *node);
          } else {
            chain.points.push_back(*node);
          }
          chain.on_border[side] = true;
        }
      }
      if (chain.points.size() == 1) continue;
      chain.base = position;
      position += static_cast<int>(chain.points.size());
      chain_pixels_.push_back(&pixel_chain);
      ++chain_count_;
    }
    positions_ = position;
  }

  // Each P point of the rectangle is attached to its nearest skeleton pixel within epsilon; if
  // that pixel is interior to a chain, simplifying that chain must keep the point within epsilon.
  // Points nearest to a chain end need nothing: ends are always vertices.
  void Attach() {
    // Per pixel: 0 for none, else 1 + (global position, or -1 for "an end somewhere"); a pixel
    // in several chains keeps the smallest (an end wins). Restored to 0 after use.
    std::vector<int>& where = ZeroedSlots(raster_.size());
    marked_.clear();
    for (size_t c = 0; c < chain_count_; ++c) {
      const auto& pixels = chain_pixels_[c]->pixels;
      const int shift = chains_[c].on_border[0] ? 1 : 0;
      const int n = static_cast<int>(pixels.size());
      for (int k = 0; k < n; ++k) {
        const bool end = !chains_[c].ring && ((k == 0 && !chains_[c].on_border[0]) ||
                                              (k == n - 1 && !chains_[c].on_border[1]));
        if (chains_[c].ring && k == n - 1) continue;  // repeats pixel 0
        const int value = 1 + (end ? -1 : chains_[c].base + k + shift);
        int& slot = where[pixels[k]];
        if (slot == 0) {
          marked_.push_back(pixels[k]);
          slot = value + 1;
        } else {
          slot = std::min(slot, value + 1);
        }
      }
    }
    const std::vector<int> disc = DiscOffsets(raster_, eps_);
    std::vector<std::pair<int, int>>& attached = attached_;  // (global position, P point)
    attached.clear();
    for (const int p : raster_.owned_delimitation()) {
      int best = -1;
      for (const int o : disc) {
        if (raster_.Has(p + o, CellRaster::kSkeleton)) {
          best = p + o;
          break;
        }
      }
      if (best < 0) continue;
      const int slot = where[best];
      if (slot <= 1) continue;  // not in a chain, or an end
      attached.emplace_back(slot - 2, p);
    }
    for (const int pixel : marked_) where[pixel] = 0;
    bucket_start_.assign(static_cast<size_t>(positions_) + 1, 0);
    for (const auto& [position, p] : attached) ++bucket_start_[position + 1];
    for (size_t i = 1; i < bucket_start_.size(); ++i) bucket_start_[i] += bucket_start_[i - 1];
    bucket_points_.resize(attached.size());
    fill_.assign(bucket_start_.begin(), bucket_start_.end() - 1);
    for (const auto& [position, p] : attached) bucket_points_[fill_[position]++] = CellPoint(p);
  }

  // Calls f(p, interior) for the P points attached to vertices i..j (i < j) of a chain being
  // simplified (vertex m is chain vertex (m + shift) mod period), vertex by vertex, until f
  // returns false (then returns false); `interior` is whether p's vertex is strictly between i and
  // j. Consecutive vertices at consecutive positions have adjacent buckets, so such a run is one
  // range of points (no per-vertex index arithmetic).
  template <typename F>
  bool ForEachAttached(const Chain& chain, int shift, int period, int i, int j, F&& f) const {
    for (int m = i; m <= j;) {
      const int offset = (m + shift) % period;
      // Vertices m..last sit at the consecutive positions offset..offset + (last - m).
      const int last = std::min(j, m + (period - 1 - offset));
      const int* const starts = bucket_start_.data() + chain.base + offset;
      const int run = last - m;
      const int end = starts[run + 1];
      // The points of vertex i and of vertex j are not interior.
      const int interior_begin = m == i ? starts[1] : starts[0];
      const int interior_end = last == j ? starts[run] : end;
      for (int k = starts[0]; k < end; ++k) {
        if (!f(bucket_points_[k], k >= interior_begin && k < interior_end)) return false;
      }
      m = last + 1;
    }
    return true;
  }

  void Simplify(size_t c, std::vector<CellPolyline>& out) {
    const Chain& chain = chains_[c];
    const auto& points = chain.points;
    const int n = static_cast<int>(points.size());
    // Vertex m of the chain being simplified is vertex (m + shift) mod period of the chain.
    int shift = 0;
    int period = n;
    auto point = [&](int m) -> const Point2& { return shift == 0 ? points[m] : rotated_[m]; };
    auto valid = [&](int i, int j) {
      const Point2& a = point(i);
      const Point2& b = point(j);
      // Epsilon-error for the points attached to the vertices it replaces; meanwhile the
      // epsilon-disc intervals of all points attached to i..j, a subset of P: if they already
      // cover the segment it is continuous (sound), else the exact test against all of P decides.
      const double length = (b - a).norm();
      const bool subset_test = length > kDistanceTolerance;
      const double ux = subset_test ? (b.x() - a.x()) / length : 0.0;
      const double uy = subset_test ? (b.y() - a.y()) / length : 0.0;
      // The epsilon-disc interval [lo, hi] of p along the segment, if it meets the segment.
      auto interval = [&](const Point2& p, double& lo, double& hi) {
        const double wx = p.x() - a.x();
        const double wy = p.y() - a.y();
        const double along = wx * ux + wy * uy;
        const double half2 = eps2_ - (wx * wx + wy * wy - along * along);
        if (half2 < 0.0) return false;
        const double half = std::sqrt(half2);
        lo = along - half;
        hi = along + half;
        return !(hi < 0.0 || lo > length);
      };
      // The intervals arrive roughly in order along the segment, so a greedy sweep in arrival
      // order decides without sorting them: each interval it takes starts within the part already
      // covered, so the sorted sweep of IntervalsCover cannot stop before the greedy one's reach.
      // Reaching `length` proves cover (the remaining points then need only the epsilon-error
      // test); taking every interval makes the greedy reach the union's, so it decides as
      // IntervalsCover would. Only if some interval was skipped does IntervalsCover decide.
      double swept = 0.0;
      bool covered = !subset_test;
      bool skipped = false;
      const bool within =
          ForEachAttached(chain, shift, period, i, j, [&](const Point2& p, bool interior) {
            if (interior && PointSegmentDistanceSquared(p, a, b) > eps2_) return false;
            if (covered) return true;
            double lo = 0.0;
            double hi = 0.0;
            if (!interval(p, lo, hi)) return true;
            if (lo <= swept + kDistanceTolerance) {
              swept = std::max(swept, hi);
              covered = swept >= length;
            } else {
              skipped = true;
            }
            return true;
          });
      if (!within) return false;
      if (subset_test) {
        if (covered || (!skipped && swept >= length - kDistanceTolerance)) return true;
        if (skipped) {
          intervals_.clear();
          ForEachAttached(chain, shift, period, i, j, [&](const Point2& p, bool) {
            double lo = 0.0;
            double hi = 0.0;
            if (interval(p, lo, hi)) intervals_.emplace_back(lo, hi);
            return true;
          });
          if (IntervalsCover(intervals_, length)) return true;
        }
      }
      return Continuous(a, b);
    };
    pieces_.clear();
    SimplifyChain(n, valid, pieces_);
    if (chain.ring && n > 3 && pieces_.size() == 1 && pieces_[0].size() > 3) {
      // A ring's first vertex is arbitrary: start again from the first corner found, which
      // usually saves that vertex.
      period = n - 1;
      shift = pieces_[0][1];
      rotated_.clear();
      for (int m = 0; m <= period; ++m) rotated_.push_back(points[(m + shift) % period]);
      std::vector<std::vector<int>> again;
      SimplifyChain(n, valid, again);
      if (again.size() == 1 && again[0].size() < pieces_[0].size()) {
        out.push_back(MakePolyline(rotated_, again[0]));
        return;
      }
      shift = 0;
    }
    const int last = n - 1;
    for (const auto& piece : pieces_) {
      CellPolyline polyline = MakePolyline(points, piece);
      polyline.start_on_border = chain.on_border[0] && piece.front() == 0;
      polyline.end_on_border = chain.on_border[1] && piece.back() == last;
      out.push_back(std::move(polyline));
    }
  }

  // A chain along a wall four cells thick (no centre line is within epsilon of both faces, and
  // hollowing keeps such a wall whole) zigzags between its faces, a vertex every few pixels. For
  // such a chain the cover stage on the chain's own P points is tried too: it draws the two faces,
  // cut at hairpins so that each face gets its own half width. The faces win if they save at least
  // two vertices (the P points nearest to the chain's ends are not attached to it, and the final
  // cover stage may need a vertex for them) and paint the cells back no worse (on blurred SLAM
  // walls they often would not).
  void ChooseCover(size_t c, size_t first, std::vector<CellPolyline>& out) {
    constexpr size_t kMinVertices = 3;
    constexpr int kMaxPixelsPerSegment = 6;  // straighter chains are left alone (and cost nothing)
    const Chain& chain = chains_[c];
    if (chain.on_border[0] || chain.on_border[1]) return;  // border nodes stitch the tiles
    size_t skeleton_vertices = 0;
    for (size_t k = first; k < out.size(); ++k) skeleton_vertices += out[k].points.size();
    const int n = static_cast<int>(chain.points.size());
    if (skeleton_vertices < kMinVertices ||
        n >= kMaxPixelsPerSegment * static_cast<int>(skeleton_vertices - 1)) {
      return;
    }
    cover_points_.clear();
    for (int k = bucket_start_[chain.base]; k < bucket_start_[chain.base + n]; ++k) {
      const Point2& p = bucket_points_[k];
      cover_points_.push_back(raster_.Index(static_cast<int>(p.x()), static_cast<int>(p.y())));
    }
    cover_.clear();
    CoverPoints(raster_, eps_, cover_points_, cover_);
    cover_ = SplitAtHairpins(cover_);
    size_t cover_vertices = 0;
    for (const CellPolyline& polyline : cover_) cover_vertices += polyline.points.size();
    if (cover_vertices + 2 > skeleton_vertices) return;
    skeleton_.assign(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
    if (PaintMatch(raster_, cover_, eps_, kMinHalfWidth) <
        PaintMatch(raster_, skeleton_, eps_, kMinHalfWidth)) {
      return;
    }
    out.resize(first);
    out.insert(out.end(), cover_.begin(), cover_.end());
  }

  CellRaster& raster_;
  BorderNodes nodes_;
  double eps_;
  double eps2_;
  std::vector<PixelChain> pixel_chains_;
  std::vector<Chain>& chains_;
  size_t chain_count_ = 0;
  std::vector<const PixelChain*> chain_pixels_;
  int positions_ = 0;
  std::vector<int> bucket_start_;
  std::vector<int> fill_;
  std::vector<Point2> bucket_points_;
  std::vector<Point2> rotated_;
  std::vector<std::vector<int>> pieces_;
  std::vector<std::pair<double, double>> intervals_;
  std::vector<int> marked_;
  std::vector<std::pair<int, int>> attached_;
  std::vector<int> cover_points_;       // ChooseCover's scratch
  std::vector<CellPolyline> cover_;     // ChooseCover's scratch
  std::vector<CellPolyline> skeleton_;  // ChooseCover's scratch
};

}  // namespace

int DefaultMargin(double epsilon) { return static_cast<int>(std::ceil(2.0 * epsilon)) + 3; }

std::vector<CellPolyline> DefaultVectorize(CellRaster& raster, const grid::OccupancyGrid& grid,
                                           const grid::StateThresholds& thresholds,
                                           double epsilon) {
  return TileRun(raster, grid, thresholds, epsilon).Run();
}

}  // namespace fleetmap::vector_map
