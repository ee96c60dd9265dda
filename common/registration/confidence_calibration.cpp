#include "common/registration/confidence_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include "common/core/check.hpp"

namespace fleetmap::registration {

ConfidenceCalibration::ConfidenceCalibration(std::vector<Knot> knots) : knots_(std::move(knots)) {
  FLEETMAP_CHECK(!knots_.empty(), "ConfidenceCalibration needs at least one knot");
  for (size_t k = 0; k < knots_.size(); ++k) {
    FLEETMAP_CHECK(knots_[k].probability >= 0.0 && knots_[k].probability <= 1.0,
                   "ConfidenceCalibration: a knot's probability is outside [0, 1]");
    if (k == 0) continue;
    FLEETMAP_CHECK(knots_[k].score > knots_[k - 1].score,
                   "ConfidenceCalibration: knot scores must increase");
    FLEETMAP_CHECK(knots_[k].probability >= knots_[k - 1].probability,
                   "ConfidenceCalibration: knot probabilities must not decrease");
  }
}

ConfidenceCalibration ConfidenceCalibration::Fit(std::vector<Sample> samples, int min_per_knot) {
  FLEETMAP_CHECK(!samples.empty(), "ConfidenceCalibration::Fit needs samples");
  std::sort(samples.begin(), samples.end(),
            [](const Sample& l, const Sample& r) { return l.score < r.score; });
  struct Block {
    double score_sum = 0.0;
    double correct = 0.0;
    double count = 0.0;
    double mean() const { return correct / count; }
    void Absorb(const Block& other) {
      score_sum += other.score_sum;
      correct += other.correct;
      count += other.count;
    }
  };
  // One block per distinct score (pairs that score alike cannot be told apart).
  std::vector<Block> blocks;
  double last_score = 0.0;
  for (const Sample& sample : samples) {
    if (blocks.empty() || sample.score != last_score) blocks.emplace_back();
    last_score = sample.score;
    blocks.back().Absorb({sample.score, sample.correct ? 1.0 : 0.0, 1.0});
  }
  // The isotonic regression (pool adjacent violators): merge while a block's rate is not above
  // its predecessor's. On single samples, not on fixed groups: a group boundary that cuts
  // through the scores where wrong placements give way to right ones, or one near miss among
  // right placements, would otherwise pool a whole range of scores into one rate.
  std::vector<Block> pooled;
  for (const Block& b : blocks) {
    pooled.push_back(b);
    while (pooled.size() > 1 && pooled[pooled.size() - 2].mean() >= pooled.back().mean()) {
      const Block last = pooled.back();
      pooled.pop_back();
      pooled.back().Absorb(last);
    }
  }
  // No knot rests on fewer than min_per_knot samples: the smallest block joins the neighbour
  // whose rate is nearer to its own (merging neighbours keeps the rates monotone).
  const double least = std::max(1, min_per_knot);
  while (pooled.size() > 1) {
    size_t small = 0;
    for (size_t k = 1; k < pooled.size(); ++k) {
      if (pooled[k].count < pooled[small].count) small = k;
    }
    if (pooled[small].count >= least) break;
    size_t into = small == 0 ? 1 : small - 1;
    if (small > 0 && small + 1 < pooled.size() &&
        std::abs(pooled[small + 1].mean() - pooled[small].mean()) <
            std::abs(pooled[small - 1].mean() - pooled[small].mean())) {
      into = small + 1;
    }
    const size_t first = std::min(small, into);
    pooled[first].Absorb(pooled[first + 1]);
    pooled.erase(pooled.begin() + static_cast<ptrdiff_t>(first) + 1);
  }
  std::vector<Knot> knots;
  for (const Block& b : pooled) {
    Knot knot{b.score_sum / b.count, (b.correct + 0.5) / (b.count + 1.0)};
    if (!knots.empty()) {
      knot.probability = std::max(knot.probability, knots.back().probability);
      if (knot.score <= knots.back().score) {
        knots.back().probability = knot.probability;
        continue;
      }
    }
    knots.push_back(knot);
  }
  return ConfidenceCalibration(std::move(knots));
}

const ConfidenceCalibration& ConfidenceCalibration::Default() {
  // Fitted by `fleetmap bench register --synthetic 24 --pairs-per-overlap 3 --skip-mexplore
  // --max-drift-per-m 0` (seed 1: 572 pairs on 24 terrains, office, maze, unstructured of
  // common/sim and warehouse, office rows, corridors of bench/register/repeated_terrain, at 20-70 %
  // overlap, each pair plain and with B drifted, labelled by whether its placement is right); the
  // real maps played no part. Refitted when the calibration set gained repeated structure and
  // drift (issue 31), when the drifted pairs were judged where B overlaps A, and when the fit
  // became the isotonic regression of the pairs themselves (2026-12-07).
  static const ConfidenceCalibration calibration({{0.0022, 0.3233},
                                                  {0.2525, 0.3625},
                                                  {0.7038, 0.6600},
                                                  {0.8297, 0.8553},
                                                  {0.9067, 0.8676},
                                                  {0.9502, 0.9000},
                                                  {0.9959, 0.9974}});
  return calibration;
}

const ConfidenceCalibration& ConfidenceCalibration::DriftTolerant() {
  // Fitted the same way with the drift-tolerant verification (`--max-drift-per-m 0.03`, the
  // RegistrationOptions default): the placement bar 0.95 sits at a score of about 0.978 (0.974
  // for the rigid one). With the fit on fixed groups of 20 pairs it sat at 0.993, which is why
  // this verification was once an option only.
  static const ConfidenceCalibration calibration(
      {{0.0294, 0.2697}, {0.8005, 0.5395}, {0.9955, 0.9912}});
  return calibration;
}

double ConfidenceCalibration::Probability(double score) const {
  if (score <= knots_.front().score) return knots_.front().probability;
  if (score >= knots_.back().score) return knots_.back().probability;
  const auto upper = std::upper_bound(knots_.begin(), knots_.end(), score,
                                      [](double s, const Knot& k) { return s < k.score; });
  const Knot& hi = *upper;
  const Knot& lo = *(upper - 1);
  const double t = (score - lo.score) / (hi.score - lo.score);
  return lo.probability + t * (hi.probability - lo.probability);
}

}  // namespace fleetmap::registration
