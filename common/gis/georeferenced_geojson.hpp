#pragma once

// A GeoJSON export of fleetmap (frame metres, with the EPSG:3857 `crs` member:
// geojson_geometry.hpp) placed on Earth: RFC 7946 GeoJSON in WGS84 longitude and latitude, for a
// fleet whose frame is surveyed (docs/file-formats.md, "GeoJSON in WGS84: --georef").
//
// Every fleetmap export is made in frame metres first, and this one step turns any of them into
// degrees, so the vector map, the terrain and the predicted free space are georeferenced by the
// same code.
//
// Thread-safety: stateless; concurrent calls are safe with a Georeference per thread.

#include <nlohmann/json.hpp>

#include "common/core/status.hpp"
#include "common/gis/georeference.hpp"

namespace fleetmap::gis {

// Decimal places of a degree the positions are rounded to: 1e-8 degree is 1.1 mm of latitude
// (and at most that of longitude). The vector maps' vertices sit on a lattice of half a cell
// (2.5 cm at 5 cm cells) within epsilon (7 cm) of the walls; 7 places (1.1 cm) would move them by
// up to half a lattice step, 8 keep them within a millimetre, and more would claim a precision no
// surveyed origin has (RFC 7946, 11.2: precision beyond the data's is misleading).
inline constexpr int kDegreeDecimals = 8;

// `collection` (a FeatureCollection of frame metres, as fleetmap's exports write it) with every
// position of every feature's geometry taken through `georeference` and written [longitude,
// latitude] rounded to kDegreeDecimals; the `crs` member removed (RFC 7946 forbids it: WGS84
// longitude and latitude is the only CRS); the top-level properties gain "georeference":
// {latitude, longitude, yaw} of the frame's origin. Feature properties that are lengths
// (half_width, thickness) stay metres.
//
// What the exports guarantee in metres holds in degrees: valid simple features, rings closed,
// shells counter-clockwise and holes clockwise (RFC 7946), no repeated positions. The transform
// keeps orientation, but it moves a vertex that lay exactly on another part's edge a rounding
// error off it, and rounding to the degree grid moves vertices by up to half a millimetre; so the
// area of each (Multi)Polygon is made again from its placed rings (FilledAreaOfRings on the degree
// grid, keeping full precision where rounding would break validity), and a line the transform
// shrinks to one position becomes a point. The point set is the same, so one feature may come
// back as several with the same properties (a polygon and a line, a line and a point).
//
// Errors (kInvalidArgument, naming the feature): a position with no place on Earth, or across the
// antimeridian (longitude 180) from the origin (RFC 7946 wants geometry cut there; fleetmap does
// not cut it), an input that is not a FeatureCollection of Point, LineString, Polygon and their
// Multi forms; kInternal if GEOS fails.
StatusOr<nlohmann::json> GeoreferencedGeoJson(const nlohmann::json& collection,
                                              const Georeference& georeference);

}  // namespace fleetmap::gis
