#include "common/gis/filled_area.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/gis/geojson_geometry.hpp"
#include "tests/support/geojson_checks.hpp"

namespace fleetmap::gis {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;
using Ring = std::vector<Point2>;

// Twice the signed area of a closed ring (positive: counter-clockwise).
double TwiceSignedArea(const Ring& ring) {
  double sum = 0.0;
  for (size_t i = 0; i + 1 < ring.size(); ++i) {
    sum += ring[i].x() * ring[i + 1].y() - ring[i + 1].x() * ring[i].y();
  }
  return sum;
}

double Area(const FilledArea& area) {
  double twice = 0.0;
  for (const SimplePolygon& polygon : area.polygons) {
    twice += TwiceSignedArea(polygon.shell);
    for (const Ring& hole : polygon.holes) twice += TwiceSignedArea(hole);
  }
  return twice / 2.0;
}

// The area exported as a FeatureCollection.
nlohmann::json Collection(const FilledArea& area) {
  nlohmann::json features = nlohmann::json::array();
  for (nlohmann::json& geometry : GeoJsonGeometries(area)) {
    features.push_back({{"type", "Feature"}, {"properties", {}}, {"geometry", geometry}});
  }
  return {{"type", "FeatureCollection"}, {"crs", GeoJsonCrs()}, {"features", features}};
}

// What GIS tools would say of the area exported as a FeatureCollection.
std::vector<std::string> Problems(const FilledArea& area) {
  return fleetmap::testing::GeoJsonProblems(Collection(area));
}

FilledArea Fill(const std::vector<Ring>& rings) {
  StatusOr<FilledArea> area = FilledAreaOfRings(rings);
  EXPECT_TRUE(area.ok()) << area.status();
  return area.ok() ? *area : FilledArea{};
}

TEST(FilledAreaTest, ValidPolygonKeepsItsVerticesShellCounterClockwiseHolesClockwise) {
  const Ring clockwise_shell = {{0, 0}, {0, 4}, {4, 4}, {4, 0}};
  const Ring counter_clockwise_hole = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  const FilledArea area = Fill({clockwise_shell, counter_clockwise_hole});
  ASSERT_EQ(area.polygons.size(), 1u);
  const SimplePolygon& polygon = area.polygons[0];
  ASSERT_EQ(polygon.shell.size(), 5u);
  EXPECT_EQ(polygon.shell.front(), polygon.shell.back());
  EXPECT_GT(TwiceSignedArea(polygon.shell), 0.0);
  ASSERT_EQ(polygon.holes.size(), 1u);
  EXPECT_EQ(polygon.holes[0].size(), 5u);
  EXPECT_LT(TwiceSignedArea(polygon.holes[0]), 0.0);
  EXPECT_DOUBLE_EQ(Area(area), 15.0);
  EXPECT_TRUE(area.lines.empty());
  EXPECT_THAT(Problems(area), IsEmpty());
}

TEST(FilledAreaTest, RingsOfOneAndTwoVerticesArePointsAndLines) {
  const FilledArea cell = Fill({{{5, 5}}});
  EXPECT_TRUE(cell.polygons.empty());
  EXPECT_THAT(cell.points, ElementsAre(Point2(5, 5)));
  const FilledArea row = Fill({{{0, 0}, {3, 0}}});
  EXPECT_TRUE(row.polygons.empty());
  ASSERT_EQ(row.lines.size(), 1u);
  EXPECT_EQ(row.lines[0].size(), 2u);
  // Repeated vertices count once: this ring is one cell.
  EXPECT_THAT(Fill({{{1, 1}, {1, 1}, {1, 1}}}).points, ElementsAre(Point2(1, 1)));
  EXPECT_THAT(Problems(cell), IsEmpty());
  EXPECT_THAT(Problems(row), IsEmpty());
}

TEST(FilledAreaTest, RingTouchingItselfSplitsIntoTwoPolygonsTouchingAtAPoint) {
  // A figure of eight through (2, 2): two squares of 4 square metres.
  const FilledArea area = Fill({{{0, 0}, {2, 0}, {2, 2}, {4, 2}, {4, 4}, {2, 4}, {2, 2}, {0, 2}}});
  EXPECT_EQ(area.polygons.size(), 2u);
  EXPECT_DOUBLE_EQ(Area(area), 8.0);
  EXPECT_TRUE(area.lines.empty());
  EXPECT_TRUE(area.points.empty());
  EXPECT_THAT(Problems(area), IsEmpty());
}

TEST(FilledAreaTest, SpikeOneCellWideBecomesALineBesideThePolygon) {
  // A square whose outline runs up from (2, 2) to (2, 5) and back: a corridor one cell wide.
  const FilledArea area = Fill({{{0, 0}, {2, 0}, {2, 2}, {2, 5}, {2, 2}, {0, 2}}});
  ASSERT_EQ(area.polygons.size(), 1u);
  EXPECT_DOUBLE_EQ(Area(area), 4.0);
  ASSERT_EQ(area.lines.size(), 1u);
  EXPECT_THAT(area.lines[0], ::testing::UnorderedElementsAre(Point2(2, 2), Point2(2, 5)));
  EXPECT_THAT(Problems(area), IsEmpty());
}

TEST(FilledAreaTest, CrossingRingsFillByTheEvenOddRule) {
  // A bow tie: two triangles of 1 square metre meeting at (1, 1).
  const FilledArea bow_tie = Fill({{{0, 0}, {2, 2}, {2, 0}, {0, 2}}});
  EXPECT_EQ(bow_tie.polygons.size(), 2u);
  EXPECT_DOUBLE_EQ(Area(bow_tie), 2.0);
  EXPECT_THAT(Problems(bow_tie), IsEmpty());
  // A "hole" crossing its shell: the cells inside both rings are not filled (4 + 4 - 2 * 1).
  const FilledArea crossed =
      Fill({{{0, 0}, {2, 0}, {2, 2}, {0, 2}}, {{1, 1}, {3, 1}, {3, 3}, {1, 3}}});
  EXPECT_DOUBLE_EQ(Area(crossed), 6.0);
  EXPECT_THAT(Problems(crossed), IsEmpty());
}

TEST(FilledAreaTest, RingRunningBackAlongItselfStillFillsTheStripBesideIt) {
  // Cell centres of a 5 cm grid, as the free-space extractor wrote them on aces3_austin: the ring
  // climbs a diagonal from (50.375, 35.325) to (51.125, 36.075) and comes straight back down it,
  // past where it started, to (50.025, 34.975). The decimal centres are not exactly collinear in
  // binary, so the spike's two sides are a rounding error apart and the strip below it is one face
  // with a sliver on top. The spike up from (50.025, 35.125) makes the ring invalid, so the faces
  // are classified by the even-odd rule; GEOSPointOnSurface's scan line met only the sliver and
  // the strip (0.04875 square metres) was left out.
  const double x0 = 50.025000000000006;  // (1000 + 0.5) * 0.05, as CellCenter computes it
  const Ring ring = {
      {x0, 34.975},     {x0, 35.125},    {x0, 35.425}, {x0, 35.125}, {50.325, 35.425000000000004},
      {50.375, 35.325}, {51.125, 36.075}};
  const FilledArea area = Fill({ring});
  EXPECT_NEAR(Area(area), 0.04875, 1e-9);
  EXPECT_THAT(Problems(area), IsEmpty());
  const fleetmap::testing::GeoJsonCoverage coverage(Collection(area));
  for (const Point2& centre :
       {Point2(50.075, 35.075), Point2(50.125, 35.125), Point2(50.325, 35.375)}) {
    EXPECT_TRUE(coverage.Covers(centre.x(), centre.y(), 0.0)) << centre.transpose();
  }
  EXPECT_FALSE(coverage.Covers(50.075, 34.975, 0.0));
}

TEST(FilledAreaTest, HoleTouchingItsShellAtAPointStaysOnePolygon) {
  const FilledArea area = Fill({{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{2, 0}, {3, 1}, {1, 1}}});
  ASSERT_EQ(area.polygons.size(), 1u);
  EXPECT_DOUBLE_EQ(Area(area), 15.0);
  EXPECT_THAT(Problems(area), IsEmpty());
}

TEST(FilledAreaTest, PointOnTheAreaIsNotRepeated) {
  const FilledArea area = Fill({{{0, 0}, {2, 0}, {2, 2}, {0, 2}}, {{2, 1}}, {{7, 7}}, {{7, 7}}});
  EXPECT_THAT(area.points, ElementsAre(Point2(7, 7)));
}

TEST(GeoJsonGeometryTest, CrsNamesEpsg3857AndPartsBecomeMultiGeometries) {
  EXPECT_EQ(GeoJsonCrs(),
            nlohmann::json::parse(
                R"({"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::3857"}})"));
  const FilledArea area =
      Fill({{{0, 0}, {2, 2}, {2, 0}, {0, 2}}, {{5, 5}}, {{8, 8}}, {{6, 0}, {7, 0}}});
  const std::vector<nlohmann::json> geometries = GeoJsonGeometries(area);
  ASSERT_EQ(geometries.size(), 3u);
  EXPECT_EQ(geometries[0]["type"], "MultiPolygon");
  EXPECT_EQ(geometries[1]["type"], "LineString");
  EXPECT_EQ(geometries[2]["type"], "MultiPoint");
  EXPECT_TRUE(GeoJsonGeometries(FilledArea{}).empty());
}

}  // namespace
}  // namespace fleetmap::gis
