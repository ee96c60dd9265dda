#pragma once

// Simplification of a chain of points with a caller-supplied full check (docs/vector-maps.md,
// kDefault step 5). Greedy with doubling: from each kept vertex the reach is doubled while the
// shortcut is valid, then bisected between the last valid and the first invalid reach. The check
// decides everything, so whatever it guarantees (here: both constraints against every delimitation
// point) holds for every emitted segment.

#include <algorithm>
#include <vector>

namespace fleetmap::vector_map {

// `valid(i, j)` (i < j < n) says whether the segment from vertex i to vertex j may replace
// vertices i..j. A unit step (j = i + 1) that is not valid breaks the chain into pieces. Appends
// the kept vertex indices of each piece (at least two, or one for a one-point chain) to `pieces`.
template <typename Valid>
void SimplifyChain(int n, Valid&& valid, std::vector<std::vector<int>>& pieces) {
  if (n == 0) return;
  std::vector<int> current = {0};
  int i = 0;
  while (i < n - 1) {
    if (!valid(i, i + 1)) {
      if (current.size() >= 2) pieces.push_back(std::move(current));
      current.clear();
      ++i;
      current.push_back(i);
      continue;
    }
    int lo = i + 1;
    int hi = -1;
    int step = 2;
    while (lo < n - 1) {
      const int candidate = std::min(i + step, n - 1);
      if (valid(i, candidate)) {
        lo = candidate;
        step *= 2;
      } else {
        hi = candidate;
        break;
      }
    }
    while (hi != -1 && hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      if (valid(i, mid)) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    current.push_back(lo);
    i = lo;
  }
  if (current.size() >= 2 || n == 1) pieces.push_back(std::move(current));
}

}  // namespace fleetmap::vector_map
