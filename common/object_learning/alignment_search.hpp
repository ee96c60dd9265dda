#pragma once

// The alignment M-step of ALGORITHMS.md 2 (eq. 26): the alignment delta of one snapshot minimises
// sum_n E[c = n] |f(mu, delta) - theta_n|^2, which equals |f(mu, delta) - theta_bar|^2 plus a
// constant, theta_bar = sum_n E[c = n] theta_n. Hill climbing over (dx, dy, dphi): try a step
// either way along each axis, take the best improving move, halve the steps when none improves,
// stop when the shift step drops below min_shift_step. Objects are seen in any orientation and a
// local climb cannot turn a snapshot half a turn, so a scan over rotations (every
// rotation_scan_step) can seed the climb.
//
// Thread-safety: stateless.

#include "common/object_learning/alignment.hpp"
#include "common/object_learning/learn_options.hpp"

namespace fleetmap::object_learning {

struct AlignmentResult {
  Alignment alignment;
  double squared_distance = 0.0;  // |f(mu, alignment) - target|^2
};

// `target` is row-major with the snapshot's size. `scan_rotations`: first try every rotation of
// the scan (at start's shift and at the shift that matches the centroids) and climb from the best;
// otherwise climb from `start` with steps `fine_factor` times the initial ones.
AlignmentResult AlignSnapshot(const scene::Patch& snapshot, const float* target,
                              const Alignment& start, bool scan_rotations, double fine_factor,
                              const EmOptions& options);

// Rotation-invariant size of a patch's content (occupancy-weighted): its mass and the standard
// deviations along its principal axes (cells). Two patches whose sizes differ a lot cannot align
// well at any rotation, so the all-pairs rotation scans (the learner's main cost: snapshots x
// objects scans) skip such pairs (issue 22: 160 snapshots of 6 shapes spent 70 % of their time
// scanning pairs of unlike shapes).
struct ShapeSize {
  double mass = 0.0;
  double major = 0.0;
  double minor = 0.0;
};
ShapeSize SizeOfContent(const float* values, int width, int height);

// Whether two contents may be the same object: masses within a factor of 2.5 and principal
// spreads within a factor of 2 (plus a cell, for tiny contents). Lenient: partial views (half a
// box seen) must still pass.
bool MayMatch(const ShapeSize& a, const ShapeSize& b);

// The alignment that puts the snapshot's centroid on the target's, unturned, and its squared
// distance (one evaluation): what a skipped pair gets instead of a scan.
AlignmentResult CentroidAlignment(const scene::Patch& snapshot, const float* target);

}  // namespace fleetmap::object_learning
