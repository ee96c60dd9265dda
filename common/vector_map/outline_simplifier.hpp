#pragma once

// Douglas-Peucker for the closed free-space outlines (OpenCV contours through cell centres) that
// never lets a guarded cell come back free: the free-space extractor guards the occupied cells
// the rasterizer will not paint, so a solid region (the inside of a blob, furniture, a thick wall)
// comes back occupied or unknown, never free.
//
// A simplified segment replaces its stretch of contour; the cells whose rasterized state can
// change are those in the "lens" between the two (a polygon: the stretch closed by the segment)
// and those the Rasterizer's scan conversion may give to the segment itself: within half a cell
// (plus kSlack, for the sub-cell moves of lattice snapping and decoding) of it along its minor
// axis. Outside every lens and band a cell keeps its even-odd parity, hence its state as the
// unsimplified contour rebuilds it, and the unsimplified contour never covers a cell outside the
// region it traces. So each segment of cv::approxPolyDP's result is checked; a segment whose lens
// or band holds a guarded cell is replaced by a checked Douglas-Peucker of its own stretch (split
// at the farthest point until both the tolerance and the check pass; single contour steps always
// pass). With no guarded cell near an outline the result is exactly cv::approxPolyDP's.
//
// Thread-safety: immutable after construction; concurrent Simplify calls are safe.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace fleetmap::vector_map {

class OutlineSimplifier {
 public:
  // Cells (x, y) with guarded(y, x) != 0 (CV_8UC1, the contours' pixel frame) must not come back
  // free. `epsilon_cells` is the Douglas-Peucker tolerance.
  OutlineSimplifier(const cv::Mat& guarded, double epsilon_cells);

  // The simplified closed ring, into `ring` (replacing its contents; a caller reuses one buffer for
  // all its contours). A result of fewer than 3 vertices encloses no guarded cell, so a caller may
  // drop such a hole.
  void Simplify(const std::vector<cv::Point>& contour, std::vector<cv::Point>* ring) const;

  // Whether a guarded cell lies in the contour's bounding box (`box`, as cv::boundingRect gives
  // it) grown by a cell (O(1)): false means nothing the contour encloses or passes is guarded.
  bool AnyGuardedNear(const cv::Rect& box) const;

  double epsilon_cells() const { return epsilon_; }

  // Sub-cell slack of the segment band (cells): covers snapping to the tile lattice (at most
  // 0.012 cells for 10 m tiles of 5 cm cells) and float noise after decoding.
  static constexpr double kSlack = 0.05;

 private:
  // Whether the segment contour[i] -> contour[j] (indices unrolled, i < j <= i + size) may stand
  // for the stretch contour[i..j] without a guarded cell coming back free.
  bool SegmentSafe(const std::vector<cv::Point>& contour, int i, int j) const;
  // Appends to `kept` the unrolled indices strictly between i and j a checked Douglas-Peucker of
  // contour[i..j] keeps.
  void Refine(const std::vector<cv::Point>& contour, int i, int j, std::vector<int>* kept) const;
  // Whether a guarded cell lies in the rectangle [x0, x1] x [y0, y1] (clipped), from the integral
  // image.
  bool AnyGuardedIn(int x0, int y0, int x1, int y1) const;
  bool Guarded(int x, int y) const {
    return x >= 0 && y >= 0 && x < guarded_.cols && y < guarded_.rows &&
           guarded_.at<uint8_t>(y, x) != 0;
  }

  cv::Mat guarded_;
  cv::Mat guarded_sum_;  // integral image of the guarded cells (CV_32S)
  double epsilon_;
  bool any_guarded_;
};

}  // namespace fleetmap::vector_map
