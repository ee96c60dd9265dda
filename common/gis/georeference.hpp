#pragma once

// Where a frame of fleetmap (the fleet frame, or a map frame) lies on Earth, and the transform of
// its metres to WGS84 longitude and latitude (docs/frames.md, "Georeference").
//
// A frame is a plane in metres; a surveyed fleet knows where its origin is (latitude, longitude)
// and which way its x axis points. Frame metres are rotated by the yaw into east / north metres
// of a local plane, and that plane is an azimuthal equidistant projection (PROJ's `aeqd`, on the
// WGS84 ellipsoid) centred on the origin, inverted to geographic coordinates: a point d metres
// from the origin in a direction lands on the ellipsoid at geodesic distance d from the origin in
// that direction. For a map of a few kilometres this is the local tangent plane a SLAM map is
// (the scale across the direction to the origin exceeds 1 by (d / R)^2 / 6: 4e-9 at 1 km, 4e-5 at
// 100 km). The geodesy is PROJ's, not ours; the whole transform is one PROJ pipeline
// (ProjPipeline) that `cct` runs the same way.
//
// Thread-safety: a Georeference may be used by one thread at a time (PROJ objects are not
// shared between threads); make one per thread. Moving it is fine.

#include <memory>
#include <string>

#include "common/core/status.hpp"
#include "common/core/types.hpp"

namespace fleetmap::gis {

// The WGS84 position of a frame's origin and the direction of its x axis. Angles in degrees.
struct GeoOrigin {
  double latitude = 0.0;   // [-90, 90], north positive
  double longitude = 0.0;  // [-180, 180], east positive
  // Counter-clockwise from East to the frame's +x axis, as in an ENU frame of REP 103: 0 = x
  // points East (and y North), 90 = x points North (y West), -90 = x points South. A compass
  // bearing b of the x axis is yaw = 90 - b.
  double yaw = 0.0;

  // kInvalidArgument naming the value: "latitude 91 is outside [-90, 90] degrees", a value that
  // is not a finite number.
  Status Validate() const;
};

// A WGS84 position in degrees, in GeoJSON's order (RFC 7946: longitude first).
struct LonLat {
  double longitude = 0.0;
  double latitude = 0.0;
};

// Farther from the origin than this, a frame is no longer a useful plane of the Earth (the scale
// is off by 0.4 %), and a position there is likelier a corrupt map than a map.
inline constexpr double kMaxGeoreferencedDistance = 1'000'000.0;  // metres

class Georeference {
 public:
  // Errors: kInvalidArgument from GeoOrigin::Validate; kInternal if PROJ cannot make the
  // pipeline (with PROJ's message).
  static StatusOr<Georeference> Create(const GeoOrigin& origin);

  Georeference(Georeference&&) noexcept;
  Georeference& operator=(Georeference&&) noexcept;
  ~Georeference();

  // The WGS84 longitude and latitude of a point given in the frame's metres; longitude in
  // [-180, 180]. Errors (kInvalidArgument, naming the point): a point farther from the origin
  // than kMaxGeoreferencedDistance, or one PROJ cannot place.
  StatusOr<LonLat> ToLonLat(const Point2& p_frame) const;

  const GeoOrigin& origin() const { return origin_; }

  // The PROJ pipeline ToLonLat runs: frame metres in, longitude and latitude in degrees out
  // (`echo "X Y 0 0" | cct -d 8 <pipeline>` gives the same numbers).
  const std::string& ProjPipeline() const { return pipeline_; }

 private:
  struct Proj;
  Georeference(const GeoOrigin& origin, std::string pipeline, std::unique_ptr<Proj> proj);

  GeoOrigin origin_;
  std::string pipeline_;
  std::unique_ptr<Proj> proj_;
};

}  // namespace fleetmap::gis
