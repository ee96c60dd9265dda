#include "common/gis/filled_area.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>

#include "common/core/number_format.hpp"
#include "common/gis/internal/geos_context.hpp"

namespace fleetmap::gis {
namespace {

using Geometry = GeosContext::Geometry;
using Ring = std::vector<Point2>;

// Consecutive repeats and a closing repeat removed: a ring of n distinct vertices in a row.
Ring WithoutRepeats(const Ring& ring) {
  Ring out;
  for (const Point2& p : ring) {
    if (out.empty() || p != out.back()) out.push_back(p);
  }
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

GEOSCoordSequence* Sequence(const GeosContext& geos, const Ring& points, bool close) {
  const unsigned size = static_cast<unsigned>(points.size() + (close ? 1 : 0));
  GEOSCoordSequence* sequence = GEOSCoordSeq_create_r(geos.handle(), size, 2);
  for (unsigned i = 0; i < size; ++i) {
    const Point2& p = points[i % points.size()];
    GEOSCoordSeq_setXY_r(geos.handle(), sequence, i, p.x(), p.y());
  }
  return sequence;
}

// Shell = the first ring, holes = the others; each with at least three distinct vertices.
Geometry PolygonOf(const GeosContext& geos, const std::vector<Ring>& rings) {
  GEOSContextHandle_t h = geos.handle();
  GEOSGeometry* shell = GEOSGeom_createLinearRing_r(h, Sequence(geos, rings.front(), true));
  std::vector<GEOSGeometry*> holes;
  for (size_t i = 1; i < rings.size(); ++i) {
    holes.push_back(GEOSGeom_createLinearRing_r(h, Sequence(geos, rings[i], true)));
  }
  return geos.Own(
      GEOSGeom_createPolygon_r(h, shell, holes.data(), static_cast<unsigned>(holes.size())));
}

// True if `p` lies inside an odd number of the rings: the even-odd rule cv::fillPoly fills by
// (a ray to +x crosses the rings' edges an odd number of times).
bool InsideOddNumberOfRings(const Point2& p, const std::vector<Ring>& rings) {
  bool inside = false;
  for (const Ring& ring : rings) {
    for (size_t i = 0; i < ring.size(); ++i) {
      const Point2& a = ring[i];
      const Point2& b = ring[(i + 1) % ring.size()];
      if ((a.y() > p.y()) == (b.y() > p.y())) continue;
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

Ring Coordinates(const GeosContext& geos, const GEOSGeometry* line) {
  const GEOSCoordSequence* sequence = GEOSGeom_getCoordSeq_r(geos.handle(), line);
  unsigned size = 0;
  GEOSCoordSeq_getSize_r(geos.handle(), sequence, &size);
  Ring out;
  for (unsigned i = 0; i < size; ++i) {
    double x = 0.0, y = 0.0;
    GEOSCoordSeq_getXY_r(geos.handle(), sequence, i, &x, &y);
    if (out.empty() || Point2(x, y) != out.back()) out.emplace_back(x, y);
  }
  return out;
}

// Distance from `p` to the segment from `a` to `b`.
double DistanceToSegment(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// A point inside `face` (a polygon GEOSPolygonize made), as far from its border as the scan below
// finds, at which to ask the even-odd rule whether the face is filled; none if the face has no
// width anywhere. GEOSPointOnSurface will not do: it scans one horizontal line, and where that
// line meets the face only in a sliver (a ring running back along itself, its two sides a rounding
// error apart because decimal cell centres are not exactly collinear in binary) it finds no
// interval wider than zero and returns the face's first vertex, a point on the border, where the
// even-odd rule is a tie: on aces3_austin a filled strip of 12 cell centres came out empty.
// Instead, scan the middle of every band between consecutive vertex heights and keep the interval
// middle with the most clearance. No vertex lies inside a band, so an edge that enters the band
// crosses all of it and edges do not cross within it: the middle of an interval is at least half
// the band's height from every vertex and no closer to any edge than to the interval's own two.
std::optional<Point2> InteriorPoint(const GeosContext& geos, const GEOSGeometry* face) {
  GEOSContextHandle_t h = geos.handle();
  struct Edge {
    Point2 low, high;  // low.y() < high.y()
  };
  std::vector<Edge> edges;
  std::vector<double> heights;
  auto add_ring = [&](const GEOSGeometry* ring) {
    const Ring closed = Coordinates(geos, ring);
    for (size_t i = 0; i + 1 < closed.size(); ++i) {
      const Point2& a = closed[i];
      const Point2& b = closed[i + 1];
      heights.push_back(a.y());
      if (a.y() != b.y()) edges.push_back(a.y() < b.y() ? Edge{a, b} : Edge{b, a});
    }
  };
  add_ring(GEOSGetExteriorRing_r(h, face));
  for (int k = 0; k < GEOSGetNumInteriorRings_r(h, face); ++k) {
    add_ring(GEOSGetInteriorRingN_r(h, face, k));
  }
  std::sort(heights.begin(), heights.end());
  heights.erase(std::unique(heights.begin(), heights.end()), heights.end());
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.low.y() < b.low.y(); });

  std::optional<Point2> best;
  double best_clearance = 0.0;
  std::vector<const Edge*> active;  // the edges crossing the current band
  size_t next = 0;
  std::vector<std::pair<double, const Edge*>> crossings;
  for (size_t i = 0; i + 1 < heights.size(); ++i) {
    const double bottom = heights[i], top = heights[i + 1];
    while (next < edges.size() && edges[next].low.y() <= bottom) active.push_back(&edges[next++]);
    std::erase_if(active, [bottom](const Edge* e) { return e->high.y() <= bottom; });
    const double y = bottom + (top - bottom) / 2.0;
    if (!(bottom < y && y < top)) continue;  // adjacent doubles: no line between them
    crossings.clear();
    for (const Edge* e : active) {
      const double x =
          e->low.x() + (y - e->low.y()) * (e->high.x() - e->low.x()) / (e->high.y() - e->low.y());
      crossings.emplace_back(x, e);
    }
    std::sort(crossings.begin(), crossings.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      const auto& [x1, left] = crossings[k];
      const auto& [x2, right] = crossings[k + 1];
      if (!(x1 < x2)) continue;
      const Point2 middle(x1 + (x2 - x1) / 2.0, y);
      const double clearance =
          std::min({(top - bottom) / 2.0, DistanceToSegment(middle, left->low, left->high),
                    DistanceToSegment(middle, right->low, right->high)});
      if (clearance > best_clearance) {
        best_clearance = clearance;
        best = middle;
      }
    }
  }
  return best;
}

// Twice the signed area of a closed ring: positive when counter-clockwise.
double TwiceSignedArea(const Ring& closed) {
  double sum = 0.0;
  for (size_t i = 0; i + 1 < closed.size(); ++i) {
    sum += closed[i].x() * closed[i + 1].y() - closed[i + 1].x() * closed[i].y();
  }
  return sum;
}

Ring Oriented(Ring closed, bool counter_clockwise) {
  if ((TwiceSignedArea(closed) > 0.0) != counter_clockwise) {
    std::reverse(closed.begin(), closed.end());
  }
  return closed;
}

void AppendPolygons(const GeosContext& geos, const GEOSGeometry* area, FilledArea* out) {
  GEOSContextHandle_t h = geos.handle();
  for (int i = 0; i < GEOSGetNumGeometries_r(h, area); ++i) {
    const GEOSGeometry* polygon = GEOSGetGeometryN_r(h, area, i);
    if (GEOSGeomTypeId_r(h, polygon) != GEOS_POLYGON || GEOSisEmpty_r(h, polygon)) continue;
    SimplePolygon simple;
    simple.shell = Oriented(Coordinates(geos, GEOSGetExteriorRing_r(h, polygon)), true);
    for (int k = 0; k < GEOSGetNumInteriorRings_r(h, polygon); ++k) {
      simple.holes.push_back(
          Oriented(Coordinates(geos, GEOSGetInteriorRingN_r(h, polygon, k)), false));
    }
    out->polygons.push_back(std::move(simple));
  }
}

void AppendLines(const GeosContext& geos, const GEOSGeometry* lines, FilledArea* out) {
  GEOSContextHandle_t h = geos.handle();
  for (int i = 0; i < GEOSGetNumGeometries_r(h, lines); ++i) {
    const GEOSGeometry* line = GEOSGetGeometryN_r(h, lines, i);
    if (GEOSGeomTypeId_r(h, line) != GEOS_LINESTRING || GEOSisEmpty_r(h, line)) continue;
    out->lines.push_back(Coordinates(geos, line));
  }
}

Status Failed(const GeosContext& geos, const char* step) {
  std::string message = "GEOS failed to ";
  message.append(step).append(": ").append(geos.last_error());
  return InternalError(std::move(message));
}

// The general case: nodes every outline against every other (the union also drops segments
// drawn twice), cuts the plane into faces along them, keeps the faces the even-odd rule fills and
// merges them into `area`; what the area does not cover (its border included) bounds no area and
// goes to `lines` (spikes, rows of cells, edges a hole shares with its shell).
Status FillByEvenOddRule(const GeosContext& geos, const std::vector<Ring>& outlines, Geometry* area,
                         Geometry* lines) {
  GEOSContextHandle_t h = geos.handle();
  std::vector<GEOSGeometry*> parts;
  for (const Ring& outline : outlines) {
    parts.push_back(GEOSGeom_createLineString_r(h, Sequence(geos, outline, true)));
  }
  const Geometry linework = geos.Own(GEOSGeom_createCollection_r(
      h, GEOS_MULTILINESTRING, parts.data(), static_cast<unsigned>(parts.size())));
  const Geometry noded = geos.Own(GEOSUnaryUnion_r(h, linework.get()));
  if (!noded) return Failed(geos, "node the outlines");
  const GEOSGeometry* noded_parts[] = {noded.get()};
  const Geometry faces = geos.Own(GEOSPolygonize_r(h, noded_parts, 1));
  if (!faces) return Failed(geos, "cut the outlines into faces");
  std::vector<Geometry> filled;
  for (int i = 0; i < GEOSGetNumGeometries_r(h, faces.get()); ++i) {
    const GEOSGeometry* face = GEOSGetGeometryN_r(h, faces.get(), i);
    // A face without width covers nothing its border does not: left out, its border is a line.
    const std::optional<Point2> inside = InteriorPoint(geos, face);
    if (inside && InsideOddNumberOfRings(*inside, outlines)) {
      filled.push_back(geos.Own(GEOSGeom_clone_r(h, face)));
    }
  }
  std::vector<GEOSGeometry*> released;
  for (Geometry& face : filled) released.push_back(face.release());
  const Geometry filled_faces = geos.Own(GEOSGeom_createCollection_r(
      h, GEOS_GEOMETRYCOLLECTION, released.data(), static_cast<unsigned>(released.size())));
  *area = geos.Own(GEOSUnaryUnion_r(h, filled_faces.get()));
  if (!*area) return Failed(geos, "merge the filled faces");
  const Geometry bare = geos.Own(GEOSDifference_r(h, noded.get(), area->get()));
  if (!bare) return Failed(geos, "subtract the area from the outlines");
  *lines = geos.Own(GEOSLineMerge_r(h, bare.get()));
  if (!*lines) return Failed(geos, "merge the bare outlines");
  return Status::Ok();
}

Point2 OnGrid(const Point2& p, int decimals) {
  return {RoundToDecimals(p.x(), decimals), RoundToDecimals(p.y(), decimals)};
}

// `ring` (closed: the last vertex repeats the first) with its vertices on the grid, consecutive
// repeats dropped; none if fewer than four positions are left.
std::optional<Ring> ClosedRingOnGrid(const Ring& ring, int decimals) {
  Ring out;
  for (const Point2& p : ring) {
    const Point2 snapped = OnGrid(p, decimals);
    if (out.empty() || snapped != out.back()) out.push_back(snapped);
  }
  if (out.size() < 4 || out.front() != out.back()) return std::nullopt;
  return out;
}

// `polygons` with every vertex on the grid, orientations kept, if GEOS finds the result still a
// valid MultiPolygon: rounding moves a vertex by up to half a grid step, which can make a sliver
// a rounding error wide cross itself, or parts touching at a point overlap.
std::optional<std::vector<SimplePolygon>> PolygonsOnGrid(const GeosContext& geos,
                                                         const std::vector<SimplePolygon>& polygons,
                                                         int decimals) {
  GEOSContextHandle_t h = geos.handle();
  std::vector<SimplePolygon> out;
  std::vector<GEOSGeometry*> parts;
  const auto release_parts = [&]() {
    for (GEOSGeometry* part : parts) GEOSGeom_destroy_r(h, part);
    return std::nullopt;
  };
  for (const SimplePolygon& polygon : polygons) {
    SimplePolygon snapped;
    std::vector<Ring> open_rings;  // PolygonOf closes them again
    for (size_t k = 0; k <= polygon.holes.size(); ++k) {
      const std::optional<Ring> ring =
          ClosedRingOnGrid(k == 0 ? polygon.shell : polygon.holes[k - 1], decimals);
      if (!ring) return release_parts();
      const Ring oriented = Oriented(*ring, k == 0);
      (k == 0 ? snapped.shell : snapped.holes.emplace_back()) = oriented;
      open_rings.emplace_back(oriented.begin(), oriented.end() - 1);
    }
    parts.push_back(PolygonOf(geos, open_rings).release());
    out.push_back(std::move(snapped));
  }
  const Geometry multi = geos.Own(GEOSGeom_createCollection_r(h, GEOS_MULTIPOLYGON, parts.data(),
                                                              static_cast<unsigned>(parts.size())));
  if (!multi || GEOSisValid_r(h, multi.get()) != 1) return std::nullopt;
  return out;
}

// Puts the polygons of `area` (valid) into `out`, with their vertices on the grid where that
// keeps them valid; else with their vertices as they are (a valid feature with a few noisy digits
// rather than a clean invalid one). GEOS's precision reduction would make them valid on the grid,
// but by dropping the collapsed sliver, and with it the cells along it the area covers.
void AppendPolygonsOnGrid(const GeosContext& geos, const GEOSGeometry* area, int decimals,
                          FilledArea* out) {
  FilledArea exact;
  AppendPolygons(geos, area, &exact);
  std::optional<std::vector<SimplePolygon>> snapped =
      PolygonsOnGrid(geos, exact.polygons, decimals);
  out->polygons = snapped ? std::move(*snapped) : std::move(exact.polygons);
}

// Lines keep their vertices on the grid unless rounding would collapse one to a point.
void SnapLinesToGrid(int decimals, FilledArea* out) {
  for (Ring& line : out->lines) {
    Ring snapped;
    for (const Point2& p : line) {
      const Point2 on_grid = OnGrid(p, decimals);
      if (snapped.empty() || on_grid != snapped.back()) snapped.push_back(on_grid);
    }
    if (snapped.size() >= 2) line = std::move(snapped);
  }
}

}  // namespace

StatusOr<FilledArea> FilledAreaOfRings(const std::vector<Ring>& rings, int decimals) {
  std::vector<Ring> outlines;  // two or more distinct vertices
  std::vector<Point2> points;  // one
  for (const Ring& ring : rings) {
    Ring cleaned = WithoutRepeats(ring);
    if (cleaned.size() == 1) points.push_back(cleaned.front());
    if (cleaned.size() >= 2) outlines.push_back(std::move(cleaned));
  }
  const GeosContext geos;
  GEOSContextHandle_t h = geos.handle();
  FilledArea out;
  Geometry area = geos.Own(nullptr);
  Geometry lines = geos.Own(nullptr);

  // Most rings are already one valid polygon (shell first, holes after): keep their vertices.
  const bool all_rings = std::all_of(outlines.begin(), outlines.end(),
                                     [](const Ring& ring) { return ring.size() >= 3; });
  if (!outlines.empty() && all_rings) {
    Geometry polygon = PolygonOf(geos, outlines);
    if (polygon && GEOSisValid_r(h, polygon.get()) == 1) area = std::move(polygon);
  }
  if (!area && !outlines.empty()) {
    FLEETMAP_RETURN_IF_ERROR(FillByEvenOddRule(geos, outlines, &area, &lines));
  }
  if (area && GEOSisValid_r(h, area.get()) != 1) {
    // Not expected of GEOS's own union; said rather than exported as an invalid polygon.
    std::string message = "GEOS made an invalid polygon: ";
    char* reason = GEOSisValidReason_r(h, area.get());
    message.append(reason != nullptr ? reason : geos.last_error());
    GEOSFree_r(h, reason);
    return InternalError(std::move(message));
  }
  if (area) AppendPolygonsOnGrid(geos, area.get(), decimals, &out);
  if (lines) AppendLines(geos, lines.get(), &out);
  SnapLinesToGrid(decimals, &out);
  for (const Point2& vertex : points) {
    const Point2 p = OnGrid(vertex, decimals);
    if (std::find(out.points.begin(), out.points.end(), p) != out.points.end()) continue;
    const Geometry point = geos.Own(GEOSGeom_createPointFromXY_r(h, p.x(), p.y()));
    const bool on_area = area && GEOSIntersects_r(h, area.get(), point.get()) == 1;
    const bool on_line = lines && GEOSIntersects_r(h, lines.get(), point.get()) == 1;
    if (!on_area && !on_line) out.points.push_back(p);
  }
  return out;
}

}  // namespace fleetmap::gis
