#pragma once

// Turns Registration::score (consistency x distinctness, a score with a stated meaning but no
// probability) into Registration::confidence: an estimate of the probability that the
// placement is right (within 3 cells at B's known centroid and 2 degrees). A monotone,
// piecewise-linear map through knots fitted by isotonic regression (pool adjacent violators) on
// labelled pairs; the default knots were fitted on synthetic pairs (office, maze and unstructured
// terrains of common/sim and the repeated-structure terrains of bench/register: warehouse shelf
// rows, office rows, corridors; every pair plain and with B drifted, labelled by whether its
// placement, found or refused, is right), never on the real evaluation maps:
// docs/registration.md says how to refit them.
//
// Immutable after construction: any thread may call its const methods.

#include <vector>

namespace fleetmap::registration {

class ConfidenceCalibration {
 public:
  struct Knot {
    double score = 0.0;
    double probability = 0.0;
  };
  struct Sample {
    double score = 0.0;
    bool correct = false;
  };

  // Knots sorted by strictly increasing score with non-decreasing probabilities in [0, 1], at
  // least one (checked: a broken table is a bug).
  explicit ConfidenceCalibration(std::vector<Knot> knots);

  // Isotonic regression of `correct` on `score` (pool adjacent violators on the samples
  // themselves), then blocks of fewer than `min_per_knot` samples merged with the neighbour of
  // nearer rate, so no knot rests on a handful of pairs; one knot per block at its mean score,
  // with probability (correct + 0.5) / (count + 1), which never claims certainty from finite
  // data. Needs at least one sample.
  static ConfidenceCalibration Fit(std::vector<Sample> samples, int min_per_knot);

  // The calibration Register uses with the rigid verification, the default
  // (docs/registration.md, "Found, confidence, overlap"), and the one it uses with the
  // drift-tolerant verification (RegistrationOptions::max_drift_per_m > 0): each fitted on the
  // scores its verification gives.
  static const ConfidenceCalibration& Default();
  static const ConfidenceCalibration& DriftTolerant();

  // The probability at `score`: interpolated between knots, the end knots' beyond them.
  double Probability(double score) const;

  const std::vector<Knot>& knots() const { return knots_; }

 private:
  std::vector<Knot> knots_;
};

}  // namespace fleetmap::registration
