#include "common/gis/filled_area.hpp"

#include <algorithm>
#include <string>

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
    const Geometry inside = geos.Own(GEOSPointOnSurface_r(h, face));
    double x = 0.0, y = 0.0;
    if (!inside || GEOSGeomGetX_r(h, inside.get(), &x) != 1 ||
        GEOSGeomGetY_r(h, inside.get(), &y) != 1) {
      return Failed(geos, "find a point inside a face");
    }
    if (InsideOddNumberOfRings(Point2(x, y), outlines)) {
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

}  // namespace

StatusOr<FilledArea> FilledAreaOfRings(const std::vector<Ring>& rings) {
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
  if (area) AppendPolygons(geos, area.get(), &out);
  if (lines) AppendLines(geos, lines.get(), &out);
  for (const Point2& p : points) {
    if (std::find(out.points.begin(), out.points.end(), p) != out.points.end()) continue;
    const Geometry point = geos.Own(GEOSGeom_createPointFromXY_r(h, p.x(), p.y()));
    const bool on_area = area && GEOSIntersects_r(h, area.get(), point.get()) == 1;
    const bool on_line = lines && GEOSIntersects_r(h, lines.get(), point.get()) == 1;
    if (!on_area && !on_line) out.points.push_back(p);
  }
  return out;
}

}  // namespace fleetmap::gis
