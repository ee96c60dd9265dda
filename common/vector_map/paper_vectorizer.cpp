#include "common/vector_map/paper_vectorizer.hpp"

#include <algorithm>
#include <cmath>

#include "common/vector_map/segment_geometry.hpp"

namespace fleetmap::vector_map {

// The paper's heuristic (ALGORITHMS.md 1): graph on P with edges between points within epsilon,
// then shortcut removal of degree-2 vertices while dist(v2, seg(v1, v3)) < epsilon.
std::vector<CellPolyline> PaperVectorize(const Delimitation& d, const CellRect& rect, double eps) {
  const double eps2 = ToleratedSquare(eps);
  std::vector<int> id(static_cast<size_t>(rect.cell_count()), -1);
  std::vector<Point2> vertex;
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
    for (int x = rect.x0; x < rect.x0 + rect.width; ++x) {
      if (!d.IsDelimitation(x, y)) continue;
      id[static_cast<size_t>(y - rect.y0) * rect.width + (x - rect.x0)] =
          static_cast<int>(vertex.size());
      vertex.emplace_back(x, y);
    }
  }
  const int n = static_cast<int>(vertex.size());
  std::vector<std::vector<int>> adjacency(n);
  const int r = static_cast<int>(std::floor(eps + kDistanceTolerance));
  for (int v = 0; v < n; ++v) {
    const int x = static_cast<int>(vertex[v].x());
    const int y = static_cast<int>(vertex[v].y());
    for (int dy = 0; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        if (dy == 0 && dx <= 0) continue;
        if (dx * dx + dy * dy > eps2 || !rect.Contains(x + dx, y + dy)) continue;
        const int u = id[static_cast<size_t>(y + dy - rect.y0) * rect.width + (x + dx - rect.x0)];
        if (u < 0) continue;
        adjacency[v].push_back(u);
        adjacency[u].push_back(v);
      }
    }
  }
  std::vector<int> queue(n);
  for (int v = 0; v < n; ++v) queue[v] = n - 1 - v;  // pop_back takes them in scan order
  std::vector<uint8_t> queued(n, 1);
  std::vector<uint8_t> removed(n, 0);
  while (!queue.empty()) {
    const int v2 = queue.back();
    queue.pop_back();
    queued[v2] = 0;
    if (adjacency[v2].size() != 2) continue;
    const int v1 = adjacency[v2][0];
    const int v3 = adjacency[v2][1];
    const double dist2 = PointSegmentDistanceSquared(vertex[v2], vertex[v1], vertex[v3]);
    if (!(dist2 < eps * eps)) continue;
    std::erase(adjacency[v1], v2);
    std::erase(adjacency[v3], v2);
    adjacency[v2].clear();
    removed[v2] = 1;
    if (std::find(adjacency[v1].begin(), adjacency[v1].end(), v3) == adjacency[v1].end()) {
      adjacency[v1].push_back(v3);
      adjacency[v3].push_back(v1);
    }
    for (const int w : {v1, v3}) {
      if (!queued[w]) {
        queued[w] = 1;
        queue.push_back(w);
      }
    }
  }
  // Decompose the remaining graph into polylines through degree-2 vertices.
  std::vector<CellPolyline> out;
  std::vector<uint8_t> visited(n, 0);
  auto terminal = [&](int v) { return adjacency[v].size() != 2; };
  auto follow = [&](int start, int first) {
    CellPolyline polyline;
    polyline.points.push_back(vertex[start]);
    int previous = start;
    int current = first;
    while (true) {
      polyline.points.push_back(vertex[current]);
      if (terminal(current) || current == start) break;
      visited[current] = 1;
      const int next =
          adjacency[current][0] == previous ? adjacency[current][1] : adjacency[current][0];
      previous = current;
      current = next;
    }
    if (polyline.points.size() >= 2 && polyline.points.front() == polyline.points.back()) {
      polyline.points.pop_back();
      polyline.closed = polyline.points.size() >= 3;
    }
    out.push_back(std::move(polyline));
  };
  for (int v = 0; v < n; ++v) {
    if (!terminal(v) || removed[v]) continue;
    if (adjacency[v].empty()) {
      out.push_back(CellPolyline{{vertex[v]}});
      continue;
    }
    for (const int u : adjacency[v]) {
      if (terminal(u)) {
        if (v < u) out.push_back(CellPolyline{{vertex[v], vertex[u]}});
      } else if (!visited[u]) {
        follow(v, u);
      }
    }
  }
  for (int v = 0; v < n; ++v) {
    if (!terminal(v) && !visited[v] && !adjacency[v].empty()) {
      visited[v] = 1;
      follow(v, adjacency[v][0]);
    }
  }
  return out;
}

}  // namespace fleetmap::vector_map
