#include "common/registration/placement_verifier.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "common/registration/registration.hpp"

namespace fleetmap::registration {
namespace {

// Occupied cells within `radius` cells of an occupied cell.
std::vector<uint8_t> NearOccupied(const grid::OccupancyGrid& g, int radius,
                                  const grid::StateThresholds& thresholds) {
  cv::Mat occupied(g.height(), g.width(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      if (g.StateAt(x, y, thresholds) == grid::CellState::kOccupied) occupied.at<uint8_t>(y, x) = 1;
    }
  }
  cv::Mat near;
  cv::dilate(occupied, near,
             cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * radius + 1, 2 * radius + 1)));
  return std::vector<uint8_t>(near.datastart, near.dataend);
}

// The shifts (in cells) within `radius` cells, nearest first, so that of two shifts that verify
// alike the smaller is kept: drift is not assumed where none is needed.
std::vector<std::pair<int, int>> ShiftsWithin(int radius) {
  std::vector<std::pair<int, int>> shifts;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      if (dx * dx + dy * dy <= radius * radius) shifts.emplace_back(dx, dy);
    }
  }
  std::stable_sort(shifts.begin(), shifts.end(), [](const auto& l, const auto& r) {
    return l.first * l.first + l.second * l.second < r.first * r.first + r.second * r.second;
  });
  return shifts;
}

// B's grid metres to A's under `t`, each point moved by its block's drift shift (none when
// `drift` is empty). The returned move refers to `t` and `drift`, which must outlive it.
auto BToA(const GridTransform& t, const DriftCorrection& drift) {
  return [&t, &drift](const Point2& p) {
    return drift.empty() ? t.Apply(p) : Point2(t.Apply(p) + drift.ShiftAt(p));
  };
}

// A's grid metres to B's: the inverse of BToA (the drift shift turned into B's frame).
auto AToB(const GridTransform& t, const DriftCorrection& drift) {
  const GridTransform b_from_a = t.Inverse();
  const double c = std::cos(t.yaw), s = std::sin(t.yaw);
  return [b_from_a, c, s, &drift](const Point2& p) {
    const Point2 q = b_from_a.Apply(p);
    if (drift.empty()) return q;
    const Point2 d = drift.ShiftAt(q);
    return Point2(q - Point2(c * d.x() + s * d.y(), -s * d.x() + c * d.y()));
  };
}

}  // namespace

GridTransform GridTransform::Inverse() const {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {-yaw, -(c * tx + s * ty), -(-s * tx + c * ty)};
}

std::vector<Point2> CellCentres(const grid::OccupancyGrid& g, grid::CellState state, int max_points,
                                const grid::StateThresholds& thresholds) {
  std::vector<Point2> all;
  const double res = g.resolution();
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      if (g.StateAt(x, y, thresholds) == state) {
        all.emplace_back((x + 0.5) * res, (y + 0.5) * res);
      }
    }
  }
  if (static_cast<int>(all.size()) <= max_points) return all;
  std::vector<Point2> thinned;
  thinned.reserve(max_points);
  const double stride = static_cast<double>(all.size()) / max_points;
  for (int i = 0; i < max_points; ++i) thinned.push_back(all[static_cast<size_t>(i * stride)]);
  return thinned;
}

DriftCorrection::DriftCorrection(double block, int columns, int rows)
    : block_(block),
      columns_(columns),
      rows_(rows),
      shifts_(static_cast<size_t>(columns) * rows, Point2(0.0, 0.0)) {}

int DriftCorrection::BlockOf(const Point2& b_point) const {
  const int x = std::clamp(static_cast<int>(std::floor(b_point.x() / block_)), 0, columns_ - 1);
  const int y = std::clamp(static_cast<int>(std::floor(b_point.y() / block_)), 0, rows_ - 1);
  return y * columns_ + x;
}

Point2 DriftCorrection::ShiftAt(const Point2& b_point) const {
  return shifts_[static_cast<size_t>(BlockOf(b_point))];
}

Point2 DriftCorrection::BlockCentre(int block_index) const {
  return {(block_index % columns_ + 0.5) * block_, (block_index / columns_ + 0.5) * block_};
}

double DriftCorrection::Largest() const {
  double largest = 0.0;
  for (const Point2& s : shifts_) largest = std::max(largest, s.norm());
  return largest;
}

int64_t PlacementVerifier::Side::Index(const Point2& p) const {
  const int x = static_cast<int>(std::floor(p.x() / res));
  const int y = static_cast<int>(std::floor(p.y() / res));
  if (x < 0 || y < 0 || x >= width || y >= height) return -1;
  return static_cast<int64_t>(y) * width + x;
}

int PlacementVerifier::Side::Judge(int64_t index) const {
  if (index < 0) return 0;
  const size_t k = static_cast<size_t>(index);
  if (near_occupied[k]) return 1;
  return state[k] == kFree ? -1 : 0;
}

void PlacementVerifier::Tally::Add(const Side& to, int64_t index, double weight) {
  const int judged = to.Judge(index);
  if (judged > 0) agree += weight;
  if (judged < 0) contradict += weight;
}

PlacementVerifier::PlacementVerifier(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b,
                                     const RegistrationOptions& options)
    : a_(MakeSide(a, options)),
      b_(MakeSide(b, options)),
      contradiction_weight_(options.verify_contradiction_weight),
      drift_block_m_(options.drift_block_m),
      max_drift_per_m_(options.max_drift_per_m),
      max_drift_cells_(options.max_drift_cells) {}

PlacementVerifier::Side PlacementVerifier::MakeSide(const grid::OccupancyGrid& g,
                                                    const RegistrationOptions& options) {
  const grid::StateThresholds& th = options.thresholds;
  Side s;
  s.width = g.width();
  s.height = g.height();
  s.res = g.resolution();
  s.state.resize(static_cast<size_t>(g.cell_count()));
  int64_t occupied = 0;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const grid::CellState state = g.StateAt(x, y, th);
      uint8_t& out = s.state[static_cast<size_t>(y) * g.width() + x];
      out = state == grid::CellState::kOccupied ? kOccupied
            : state == grid::CellState::kFree   ? kFree
                                                : kUnknown;
      occupied += out == kOccupied;
    }
  }
  s.near_occupied = NearOccupied(g, options.tolerance_cells, th);
  s.occupied_points = CellCentres(g, grid::CellState::kOccupied, options.max_refine_points, th);
  if (!s.occupied_points.empty()) {
    s.occupied_weight = static_cast<double>(occupied) / s.occupied_points.size();
  }
  return s;
}

PlacementVerifier::Tally PlacementVerifier::Occupied(const Side& from, const Side& to,
                                                     const GridTransform& t) {
  Tally tally;
  for (const Point2& p : from.occupied_points)
    tally.Add(to, to.Index(t.Apply(p)), from.occupied_weight);
  return tally;
}

PlacementVerifier::Verdict PlacementVerifier::Verify(const GridTransform& t) const {
  const Tally b_in_a = Occupied(b_, a_, t);
  const Tally a_in_b = Occupied(a_, b_, t.Inverse());
  Verdict v;
  v.agree = b_in_a.agree + a_in_b.agree;
  v.contradict = b_in_a.contradict + a_in_b.contradict;
  v.value = v.agree - contradiction_weight_ * v.contradict;
  return v;
}

PlacementVerifier::Verdict PlacementVerifier::VerifyWithDrift(const GridTransform& t) const {
  if (!(max_drift_per_m_ > 0.0) || max_drift_cells_ < 1) return Verify(t);  // rigid
  // The rigid fit is exact where the two maps agree and drift grows away from there: the centre
  // of the rigidly agreeing samples (A's grid metres) is where blocks may not move at all.
  Point2 anchor(0.0, 0.0);
  double weight = 0.0;
  for (const Point2& p : b_.occupied_points) {
    const Point2 q = t.Apply(p);
    const int64_t i = a_.Index(q);
    if (i >= 0 && a_.near_occupied[static_cast<size_t>(i)]) {
      anchor += b_.occupied_weight * q;
      weight += b_.occupied_weight;
    }
  }
  const GridTransform b_from_a = t.Inverse();
  for (const Point2& p : a_.occupied_points) {
    const int64_t i = b_.Index(b_from_a.Apply(p));
    if (i >= 0 && b_.near_occupied[static_cast<size_t>(i)]) {
      anchor += a_.occupied_weight * p;
      weight += a_.occupied_weight;
    }
  }
  if (weight == 0.0) return Verify(t);
  return ShiftBlocks(t, anchor / weight);
}

PlacementVerifier::Verdict PlacementVerifier::ShiftBlocks(const GridTransform& t,
                                                          const Point2& anchor) const {
  const double res = a_.res;
  const int columns = std::max(1, static_cast<int>(std::ceil(b_.width * b_.res / drift_block_m_)));
  const int rows = std::max(1, static_cast<int>(std::ceil(b_.height * b_.res / drift_block_m_)));
  Verdict v;
  v.drift = DriftCorrection(drift_block_m_, columns, rows);
  // Each block's samples: B's moved rigidly into A, and A's that land in the block, in B.
  const GridTransform b_from_a = t.Inverse();
  std::vector<std::vector<Point2>> b_in_a(static_cast<size_t>(v.drift.block_count()));
  std::vector<std::vector<Point2>> a_in_b(b_in_a.size());
  for (const Point2& p : b_.occupied_points) {
    b_in_a[static_cast<size_t>(v.drift.BlockOf(p))].push_back(t.Apply(p));
  }
  for (const Point2& p : a_.occupied_points) {
    const Point2 q = b_from_a.Apply(p);
    if (b_.Index(q) >= 0) a_in_b[static_cast<size_t>(v.drift.BlockOf(q))].push_back(q);
  }
  const double c = std::cos(t.yaw), s = std::sin(t.yaw);
  const std::vector<std::pair<int, int>> all_shifts = ShiftsWithin(max_drift_cells_);
  for (int k = 0; k < v.drift.block_count(); ++k) {
    const auto& from_b = b_in_a[static_cast<size_t>(k)];
    const auto& from_a = a_in_b[static_cast<size_t>(k)];
    // A block shifted by d on A: B's samples land at q + d, A's at q - R^T d on B.
    const auto verify_shift = [&](const Point2& d) {
      Tally tally;
      for (const Point2& q : from_b) tally.Add(a_, a_.Index(q + d), b_.occupied_weight);
      const Point2 back(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
      for (const Point2& q : from_a) tally.Add(b_, b_.Index(q - back), a_.occupied_weight);
      return tally;
    };
    Tally best = verify_shift(Point2(0.0, 0.0));
    const double distance = (t.Apply(v.drift.BlockCentre(k)) - anchor).norm();
    const int radius =
        std::min(max_drift_cells_, static_cast<int>(std::floor(max_drift_per_m_ * distance / res)));
    if (radius >= 1 && !(from_b.empty() && from_a.empty())) {
      Point2 best_shift(0.0, 0.0);
      double best_value = best.Value(contradiction_weight_);
      for (const auto& [dx, dy] : all_shifts) {
        if (dx * dx + dy * dy > radius * radius) break;  // nearest first
        const Point2 d(dx * res, dy * res);
        const Tally tally = verify_shift(d);
        if (tally.Value(contradiction_weight_) > best_value) {
          best = tally;
          best_value = tally.Value(contradiction_weight_);
          best_shift = d;
        }
      }
      v.drift.Set(k, best_shift);
    }
    v.agree += best.agree;
    v.contradict += best.contradict;
  }
  v.value = v.agree - contradiction_weight_ * v.contradict;
  return v;
}

template <typename Move>
Evidence PlacementVerifier::CompareCells(const Side& from, const Side& to, Move moved) {
  Evidence e;
  for (int y = 0; y < from.height; ++y) {
    for (int x = 0; x < from.width; ++x) {
      const uint8_t state = from.state[static_cast<size_t>(y) * from.width + x];
      if (state == kUnknown) continue;
      ++e.known;
      const int64_t i = to.Index(moved(Point2((x + 0.5) * from.res, (y + 0.5) * from.res)));
      if (i < 0) continue;
      const size_t k = static_cast<size_t>(i);
      if (to.state[k] == kUnknown) continue;
      ++e.known_shared;
      if (state != kOccupied) continue;
      ++e.occupied_shared;
      if (to.near_occupied[k]) {
        ++e.agree;
      } else if (to.state[k] == kFree) {
        ++e.contradict;
      }
    }
  }
  return e;
}

Evidence PlacementVerifier::BInA(const GridTransform& t, const DriftCorrection& drift) const {
  return CompareCells(b_, a_, BToA(t, drift));
}

Evidence PlacementVerifier::AInB(const GridTransform& t, const DriftCorrection& drift) const {
  return CompareCells(a_, b_, AToB(t, drift));
}

template <typename MoveFirst, typename MoveSecond>
void PlacementVerifier::CountDisagreements(const Side& from, const Side& to, MoveFirst first,
                                           MoveSecond second, Discrimination* d) {
  for (int y = 0; y < from.height; ++y) {
    for (int x = 0; x < from.width; ++x) {
      if (from.state[static_cast<size_t>(y) * from.width + x] != kOccupied) continue;
      const Point2 p((x + 0.5) * from.res, (y + 0.5) * from.res);
      const int under_first = to.Judge(to.Index(first(p)));
      const int under_second = to.Judge(to.Index(second(p)));
      if (under_first > 0 && under_second < 0) ++d->for_first;
      if (under_second > 0 && under_first < 0) ++d->for_second;
    }
  }
}

Discrimination PlacementVerifier::Discriminate(const GridTransform& first,
                                               const DriftCorrection& first_drift,
                                               const GridTransform& second,
                                               const DriftCorrection& second_drift) const {
  Discrimination d;
  CountDisagreements(b_, a_, BToA(first, first_drift), BToA(second, second_drift), &d);
  CountDisagreements(a_, b_, AToB(first, first_drift), AToB(second, second_drift), &d);
  return d;
}

}  // namespace fleetmap::registration
