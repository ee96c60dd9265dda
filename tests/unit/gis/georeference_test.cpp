// The frame -> WGS84 transform against figures computed without it: the direct geodesic problem
// solved by PROJ's `geod` tool (GeographicLib: from a point, an azimuth clockwise from North and a
// distance to the point reached; each figure's command is given), and the length of the equator
// (WGS84's a = 6378137 m, so a degree of longitude there is 2 pi a / 360 = 111319.49079 m).

#include "common/gis/georeference.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "common/process/subprocess.hpp"

namespace fleetmap::gis {
namespace {

using ::testing::HasSubstr;

// 1e-9 degree is 0.1 mm: far below what the figures could be told apart by, far above doubles'
// noise.
constexpr double kDegreeTolerance = 1e-9;

MATCHER_P2(IsLonLat, longitude, latitude,
           "is within 1e-9 degree of (" + ::testing::PrintToString(longitude) + ", " +
               ::testing::PrintToString(latitude) + ")") {
  *result_listener << "is (" << ::testing::PrintToString(arg.longitude) << ", "
                   << ::testing::PrintToString(arg.latitude) << ")";
  return std::abs(arg.longitude - longitude) <= kDegreeTolerance &&
         std::abs(arg.latitude - latitude) <= kDegreeTolerance;
}

LonLat Place(const GeoOrigin& origin, const Point2& p_frame) {
  StatusOr<Georeference> georeference = Georeference::Create(origin);
  EXPECT_TRUE(georeference.ok()) << georeference.status();
  if (!georeference.ok()) return {};
  StatusOr<LonLat> lon_lat = georeference->ToLonLat(p_frame);
  EXPECT_TRUE(lon_lat.ok()) << lon_lat.status();
  return lon_lat.ok() ? *lon_lat : LonLat{};
}

TEST(GeoreferenceTest, TheOriginIsTheGivenPlace) {
  EXPECT_THAT(Place({.latitude = 52.5, .longitude = 13.4, .yaw = 37.0}, Point2(0.0, 0.0)),
              IsLonLat(13.4, 52.5));
  EXPECT_THAT(Place({.latitude = -33.45, .longitude = -70.66, .yaw = 0.0}, Point2(0.0, 0.0)),
              IsLonLat(-70.66, -33.45));
}

// Yaw 0: x points East, y North (ENU).
// echo "52.5 13.4 0 1000" | geod +ellps=WGS84 -f %.12f   -> 52.508986589658 13.400000000000
TEST(GeoreferenceTest, AtYawZeroAKilometreAlongYIsAKilometreNorth) {
  EXPECT_THAT(Place({.latitude = 52.5, .longitude = 13.4, .yaw = 0.0}, Point2(0.0, 1000.0)),
              IsLonLat(13.4, 52.508986589658));
}

// Yaw 90: x points North and y West.
// echo "52.5 13.4 270 1000" | geod +ellps=WGS84 -f %.12f -> 52.499999083834 13.385274679003
TEST(GeoreferenceTest, AYawOf90TurnsXToNorthAndYToWest) {
  const GeoOrigin origin{.latitude = 52.5, .longitude = 13.4, .yaw = 90.0};
  EXPECT_THAT(Place(origin, Point2(1000.0, 0.0)), IsLonLat(13.4, 52.508986589658));
  EXPECT_THAT(Place(origin, Point2(0.0, 1000.0)), IsLonLat(13.385274679003, 52.499999083834));
}

// A kilometre along the equator is 1000 / 111319.49079327357 degrees of longitude, exactly: the
// geodesic between two points of the equator (closer than about 19970 km) is the equator.
TEST(GeoreferenceTest, AKilometreEastOnTheEquatorIsTheEquatorsArc) {
  const double degree_of_equator = 2.0 * std::numbers::pi * 6378137.0 / 360.0;
  EXPECT_THAT(Place({.latitude = 0.0, .longitude = 0.0, .yaw = 0.0}, Point2(1000.0, 0.0)),
              IsLonLat(1000.0 / degree_of_equator, 0.0));
  EXPECT_THAT(Place({.latitude = 0.0, .longitude = 100.0, .yaw = 180.0}, Point2(1000.0, 0.0)),
              IsLonLat(100.0 - 1000.0 / degree_of_equator, 0.0));
}

// Yaw 30 at 45 N 7 E, the point (300, -400): 500 m at 30 + atan2(-400, 300) = -23.1301 degrees
// counter-clockwise from East, an azimuth of 90 - (-23.1301) = 113.130102354156 degrees.
// echo "45 7 113.130102354156 500" | geod +ellps=WGS84 -f %.12f -> 44.998232488113 7.005831476744
TEST(GeoreferenceTest, AnyYawAndDirectionIsTheGeodesicFromTheOrigin) {
  EXPECT_THAT(Place({.latitude = 45.0, .longitude = 7.0, .yaw = 30.0}, Point2(300.0, -400.0)),
              IsLonLat(7.005831476744, 44.998232488113));
}

// South and West: yaw -90 turns x to the South.
// echo "-33.45 -70.66 180 250" | geod +ellps=WGS84 -f %.12f -> -33.452254028838 -70.660000000000
TEST(GeoreferenceTest, SouthernAndWesternHemispheres) {
  EXPECT_THAT(Place({.latitude = -33.45, .longitude = -70.66, .yaw = -90.0}, Point2(250.0, 0.0)),
              IsLonLat(-70.66, -33.452254028838));
}

TEST(GeoreferenceTest, BadOriginsAreRefusedNamingTheValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    GeoOrigin origin;
    std::string message;
  };
  for (const Case& c : {
           Case{{.latitude = 90.5, .longitude = 0.0, .yaw = 0.0},
                "latitude 90.5 is outside [-90, 90] degrees"},
           Case{{.latitude = -91.0, .longitude = 0.0, .yaw = 0.0}, "latitude -91 is outside"},
           Case{{.latitude = 0.0, .longitude = 180.01, .yaw = 0.0},
                "longitude 180.01 is outside [-180, 180] degrees"},
           Case{{.latitude = 0.0, .longitude = -181.0, .yaw = 0.0}, "longitude -181 is outside"},
           Case{{.latitude = nan, .longitude = 0.0, .yaw = 0.0}, "latitude nan is not a finite"},
           Case{{.latitude = 0.0, .longitude = inf, .yaw = 0.0}, "longitude inf is not a finite"},
           Case{{.latitude = 0.0, .longitude = 0.0, .yaw = nan}, "yaw nan is not a finite"},
       }) {
    const StatusOr<Georeference> made = Georeference::Create(c.origin);
    ASSERT_FALSE(made.ok()) << c.message;
    EXPECT_EQ(made.status().code(), StatusCode::kInvalidArgument);
    EXPECT_THAT(made.status().message(), HasSubstr(c.message));
  }
  // The edges themselves are places.
  EXPECT_TRUE(Georeference::Create({.latitude = -90.0, .longitude = 180.0, .yaw = 0.0}).ok());
  EXPECT_TRUE(Georeference::Create({.latitude = 90.0, .longitude = -180.0, .yaw = 720.0}).ok());
}

TEST(GeoreferenceTest, APointFartherThan1000KmIsAnErrorNamingIt) {
  StatusOr<Georeference> georeference =
      Georeference::Create({.latitude = 10.0, .longitude = 20.0, .yaw = 0.0});
  ASSERT_TRUE(georeference.ok()) << georeference.status();
  EXPECT_TRUE(georeference->ToLonLat(Point2(0.0, 999'000.0)).ok());
  const StatusOr<LonLat> far = georeference->ToLonLat(Point2(800'000.0, -700'000.0));
  ASSERT_FALSE(far.ok());
  EXPECT_THAT(far.status().message(), HasSubstr("(800000, -700000) m"));
  EXPECT_THAT(far.status().message(), HasSubstr("farther than 1000 km"));
  EXPECT_FALSE(georeference->ToLonLat(Point2(std::nan(""), 0.0)).ok());
}

// The pipeline the side file records is the transform itself: PROJ's `cct` tool, run on it,
// gives the same longitude and latitude.
TEST(GeoreferenceTest, CctRunsThePipelineToTheSameNumbers) {
  StatusOr<Georeference> georeference =
      Georeference::Create({.latitude = 45.0, .longitude = 7.0, .yaw = 30.0});
  ASSERT_TRUE(georeference.ok()) << georeference.status();
  EXPECT_THAT(georeference->ProjPipeline(), HasSubstr("+inv +proj=aeqd +lat_0=45 +lon_0=7"));
  const process::CommandResult cct = process::RunCommand(
      {"/bin/sh", "-c", "echo '300 -400 0 0' | /usr/bin/cct -d 10 " + georeference->ProjPipeline()},
      std::chrono::seconds(30));
  ASSERT_EQ(cct.exit_code, 0) << cct.output() << " (cct is in proj-bin: make deps)";
  std::istringstream columns(cct.out);
  LonLat from_cct;
  columns >> from_cct.longitude >> from_cct.latitude;
  EXPECT_THAT(from_cct, IsLonLat(7.005831476744, 44.998232488113)) << cct.out;
  const StatusOr<LonLat> ours = georeference->ToLonLat(Point2(300.0, -400.0));
  ASSERT_TRUE(ours.ok()) << ours.status();
  EXPECT_THAT(*ours, IsLonLat(from_cct.longitude, from_cct.latitude));
}

TEST(GeoreferenceTest, MovesKeepTheTransform) {
  StatusOr<Georeference> made =
      Georeference::Create({.latitude = 52.5, .longitude = 13.4, .yaw = 0.0});
  ASSERT_TRUE(made.ok()) << made.status();
  Georeference moved = std::move(made).value();
  const StatusOr<LonLat> north = moved.ToLonLat(Point2(0.0, 1000.0));
  ASSERT_TRUE(north.ok()) << north.status();
  EXPECT_THAT(*north, IsLonLat(13.4, 52.508986589658));
  EXPECT_EQ(moved.origin().latitude, 52.5);
}

}  // namespace
}  // namespace fleetmap::gis
