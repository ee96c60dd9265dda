// The VectorTile codec (layout in docs/file-formats.md).

#include "common/transport/internal/vector_tile_codec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "common/vector_map/rasterizer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::transport {
namespace {

using ::testing::HasSubstr;
using vector_map::FreePolygon;
using vector_map::Polyline;
using vector_map::TileQuantum;
using VectorTileIdl = fleetmap_msgs::msg::dds_::VectorTile_;

constexpr double kTileSize = 10.0;
const TileId kTile{1, -2};

// The point (i, j) quanta from kTile's corner, computed as the decoder does: on the lattice, as
// the vectorizer makes them.
Point2 At(int i, int j) {
  const double q = TileQuantum(kTileSize);
  constexpr double n = vector_map::kTileQuantaPerSide;
  return {(kTile.x * n + i) * q, (kTile.y * n + j) * q};
}

// Whole half-width steps of the tiles' epsilon, as the vectorizer makes half widths on the lattice.
double Steps(int n) { return n * vector_map::HalfWidthStep(0.0707); }

VectorTileMessage TileWith(std::vector<Polyline> obstacles, std::vector<FreePolygon> free = {}) {
  VectorTileMessage message;
  message.robot_id = RobotId{"alpha"};
  message.tile = kTile;
  message.tile_size = kTileSize;
  message.map.frame_id = "fleet";
  message.map.resolution = 0.05;
  message.map.epsilon = 0.0707;
  message.map.obstacles = std::move(obstacles);
  message.map.free_space = std::move(free);
  return message;
}

VectorTileIdl Encoded(const VectorTileMessage& message) {
  StatusOr<VectorTileIdl> idl = ToIdl(message);
  EXPECT_TRUE(idl.ok()) << idl.status();
  return idl.ok() ? *std::move(idl) : VectorTileIdl();
}

std::vector<Polyline> Decoded(const VectorTileIdl& idl) {
  StatusOr<VectorTileMessage> back = FromIdl(idl);
  EXPECT_TRUE(back.ok()) << back.status();
  return back.ok() ? back->map.obstacles : std::vector<Polyline>();
}

// The order FromIdl gives obstacles back in: polylines, then point obstacles, each as given.
std::vector<Polyline> WireOrder(std::vector<Polyline> obstacles) {
  std::stable_partition(obstacles.begin(), obstacles.end(),
                        [](const Polyline& p) { return p.points.size() != 1; });
  return obstacles;
}

// The cells a map paints over a 20 x 20 m grid around kTile.
grid::OccupancyGrid Painted(const std::vector<Polyline>& obstacles) {
  vector_map::VectorMap map;
  map.epsilon = 0.0707;
  map.obstacles = obstacles;
  const Pose2 origin{kTile.x * kTileSize - 5.0, kTile.y * kTileSize - 5.0, 0.0};
  StatusOr<grid::OccupancyGrid> cells =
      vector_map::Rasterizer().Rasterize(map, 400, 400, 0.05, origin);
  EXPECT_TRUE(cells.ok()) << cells.status();
  return cells.ok() ? *std::move(cells) : grid::OccupancyGrid();
}

TEST(VectorTileCodecTest, PointObstaclesTravelInThePointArrays) {
  const Polyline line{{At(0, 0), At(100, 0)}, false, 0.0};
  const Polyline speck{{At(7, 8)}, false, 0.0};
  const Polyline fat_speck{{At(9, 10)}, false, Steps(41)};
  const Polyline ring{{At(10, 10), At(20, 10), At(20, 20)}, true, 0.0};
  const VectorTileIdl idl = Encoded(TileWith({line, speck, ring, fat_speck}));
  EXPECT_EQ(idl.obstacle_sizes(), (std::vector<uint8_t>{2, 4}));
  EXPECT_TRUE(idl.obstacle_half_widths().empty());  // all 0
  EXPECT_EQ(idl.point_x(), (std::vector<int16_t>{7, 9}));
  EXPECT_EQ(idl.point_y(), (std::vector<int16_t>{8, 10}));
  EXPECT_EQ(idl.point_half_widths(), (std::vector<uint8_t>{0, 41}));
  // Exactly what went in: points come back as one-vertex open polylines, after the others.
  EXPECT_EQ(Decoded(idl), (std::vector<Polyline>{line, ring, speck, fat_speck}));
}

TEST(VectorTileCodecTest, HalfWidthsTravelAsStepsOfEpsilonAndEpsilonAlwaysFits) {
  // The tile carries epsilon as a float; 254 steps of it make epsilon, so a half width of exactly
  // the (double) epsilon still fits in 255 steps whichever way the float rounded.
  for (const double epsilon : {0.0707, 0.07071067811865477, 0.1414213562373095, 0.0353553, 0.3}) {
    VectorTileMessage message = TileWith({Polyline{{At(0, 0), At(100, 0)}, false, epsilon}});
    message.map.epsilon = epsilon;
    const VectorTileIdl idl = Encoded(message);
    ASSERT_EQ(idl.obstacle_half_widths().size(), 1u);
    EXPECT_GE(idl.obstacle_half_widths()[0], vector_map::kHalfWidthStepsPerEpsilon);
    const std::vector<Polyline> back = Decoded(idl);
    ASSERT_EQ(back.size(), 1u);
    EXPECT_GE(back[0].half_width, epsilon) << epsilon;
    EXPECT_LT(back[0].half_width, epsilon * 1.005) << epsilon;
    // Beyond epsilon is not a half width the constraints allow: refused, naming both.
    message.map.obstacles[0].half_width = epsilon * 1.01;
    EXPECT_THAT(ToIdl(message).status().message(), HasSubstr("is not within epsilon"));
  }
}

TEST(VectorTileCodecTest, ClosedPolylinesRepeatTheirFirstVertex) {
  const Polyline triangle{{At(10, 10), At(20, 10), At(20, 20)}, true, Steps(3)};
  const Polyline open_triangle{{At(10, 10), At(20, 10), At(20, 20)}, false, Steps(3)};
  const VectorTileIdl idl = Encoded(TileWith({triangle, open_triangle}));
  EXPECT_EQ(idl.obstacle_sizes(), (std::vector<uint8_t>{4, 3}));
  EXPECT_EQ(idl.obstacle_x(), (std::vector<int16_t>{10, 20, 20, 10, 10, 20, 20}));
  EXPECT_EQ(idl.obstacle_y(), (std::vector<int16_t>{10, 10, 20, 10, 10, 10, 20}));
  EXPECT_EQ(idl.obstacle_half_widths(), (std::vector<uint8_t>{3, 3}));
  EXPECT_EQ(Decoded(idl), (std::vector<Polyline>{triangle, open_triangle}));

  // A closed ring whose last vertex already equals its first keeps it.
  const Polyline repeated{{At(1, 1), At(5, 1), At(5, 5), At(1, 1)}, true, 0.0};
  EXPECT_EQ(Decoded(Encoded(TileWith({repeated}))), std::vector<Polyline>{repeated});
  // Three vertices returning to the first are an open polyline (n < 4): two segments.
  const Polyline there_and_back{{At(1, 1), At(5, 1), At(1, 1)}, false, 0.0};
  EXPECT_EQ(Decoded(Encoded(TileWith({there_and_back}))), std::vector<Polyline>{there_and_back});
}

TEST(VectorTileCodecTest, DegenerateClosednessTakesItsCanonicalForm) {
  // closed adds a segment only from three vertices on (Polyline::SegmentCount), so a closed
  // polyline of two vertices is the open one, and a closed point is a point.
  const Polyline closed_pair{{At(1, 1), At(5, 1)}, true, 0.0};
  const Polyline closed_point{{At(3, 3)}, true, Steps(2)};
  const std::vector<Polyline> back = Decoded(Encoded(TileWith({closed_pair, closed_point})));
  EXPECT_EQ(back, (std::vector<Polyline>{Polyline{{At(1, 1), At(5, 1)}, false, 0.0},
                                         Polyline{{At(3, 3)}, false, Steps(2)}}));
  EXPECT_EQ(back[0].SegmentCount(), closed_pair.SegmentCount());
}

TEST(VectorTileCodecTest, AnOpenLoopComesBackClosedAndPaintsTheSameCells) {
  // The vectorizer never emits this (MakePolyline closes such pieces), but another writer may:
  // n >= 4 vertices whose last is the first read as the closed ring, with the same segments.
  const Polyline loop{
      {At(200, 200), At(1800, 200), At(1800, 1500), At(200, 1500), At(200, 200)}, false, Steps(40)};
  const std::vector<Polyline> back = Decoded(Encoded(TileWith({loop})));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_TRUE(back[0].closed);
  EXPECT_EQ(back[0].points, std::vector<Point2>(loop.points.begin(), loop.points.end() - 1));
  EXPECT_EQ(back[0].half_width, loop.half_width);
  EXPECT_EQ(back[0].SegmentCount(), loop.SegmentCount());
  const grid::OccupancyGrid before = Painted({loop});
  EXPECT_GT(std::count(before.data().begin(), before.data().end(), grid::kOccupiedValue), 50);
  EXPECT_EQ(Painted(back).data(), before.data());
}

// Distinct lattice points of kTile, on a zigzag: (i % 128) * 64, (i / 128) * 16 quanta.
std::vector<Point2> ManyPoints(size_t count) {
  std::vector<Point2> points;
  for (size_t i = 0; i < count; ++i) {
    points.push_back(At(static_cast<int>(i % 128) * 64, static_cast<int>(i / 128) * 16));
  }
  return points;
}

TEST(VectorTileCodecTest, ALongOpenPolylineIsSplitIntoPiecesSharingTheirEnds) {
  const Polyline wall{ManyPoints(2 * 255 + 10), false, Steps(5)};
  const VectorTileIdl idl = Encoded(TileWith({wall}));
  // 520 vertices: 255, then 255 from the 255th, then the last 12 from the 509th.
  EXPECT_EQ(idl.obstacle_sizes(), (std::vector<uint8_t>{255, 255, 12}));
  const std::vector<Polyline> pieces = Decoded(idl);
  ASSERT_EQ(pieces.size(), 3u);
  std::vector<Point2> joined;
  for (const Polyline& piece : pieces) {
    EXPECT_FALSE(piece.closed);
    EXPECT_EQ(piece.half_width, wall.half_width);
    if (!joined.empty()) {
      EXPECT_EQ(piece.points.front(), joined.back());
      joined.pop_back();
    }
    joined.insert(joined.end(), piece.points.begin(), piece.points.end());
  }
  EXPECT_EQ(joined, wall.points);
  size_t segments = 0;
  for (const Polyline& piece : pieces) segments += piece.SegmentCount();
  EXPECT_EQ(segments, wall.SegmentCount());
}

TEST(VectorTileCodecTest, ALongClosedPolylineBecomesOpenPiecesWithAllItsSegments) {
  // 255 vertices closed: 256 on the wire with the repeated first, one too many.
  const Polyline ring{ManyPoints(255), true, 0.0};
  const VectorTileIdl idl = Encoded(TileWith({ring}));
  EXPECT_EQ(idl.obstacle_sizes(), (std::vector<uint8_t>{255, 2}));
  const std::vector<Polyline> pieces = Decoded(idl);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_FALSE(pieces[0].closed);
  EXPECT_FALSE(pieces[1].closed);
  EXPECT_EQ(pieces[0].points, ring.points);
  // The last piece is the closing segment.
  EXPECT_EQ(pieces[1].points, (std::vector<Point2>{ring.points.back(), ring.points.front()}));
  EXPECT_EQ(pieces[0].SegmentCount() + pieces[1].SegmentCount(), ring.SegmentCount());
  // One vertex fewer fits whole and stays closed.
  const Polyline fits{ManyPoints(254), true, 0.0};
  EXPECT_EQ(Decoded(Encoded(TileWith({fits}))), std::vector<Polyline>{fits});
}

TEST(VectorTileCodecTest, FreeRingsAndPolygonsTooLargeForTheCountsAreRefused) {
  const FreePolygon fits{ManyPoints(65535), {}};
  const StatusOr<VectorTileIdl> ok = ToIdl(TileWith({}, {fits}));
  ASSERT_TRUE(ok.ok()) << ok.status();
  EXPECT_EQ(ok->free_ring_sizes(), std::vector<uint16_t>{65535});

  const FreePolygon long_ring{ManyPoints(65536), {}};
  const StatusOr<VectorTileIdl> too_long = ToIdl(TileWith({}, {long_ring}));
  EXPECT_EQ(too_long.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(too_long.status().message(), HasSubstr("a free ring has 65536 vertices"));
  EXPECT_THAT(too_long.status().message(), HasSubstr("65535"));

  const FreePolygon long_hole{ManyPoints(4), {ManyPoints(3), ManyPoints(65536)}};
  EXPECT_THAT(ToIdl(TileWith({}, {long_hole})).status().message(),
              HasSubstr("a free ring has 65536 vertices"));

  FreePolygon holes{{At(0, 0), At(9000, 0), At(9000, 9000)}, {}};
  holes.holes.assign(65535, {At(100, 100)});
  const StatusOr<VectorTileIdl> too_many = ToIdl(TileWith({}, {holes}));
  EXPECT_EQ(too_many.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(too_many.status().message(), HasSubstr("a free polygon has 65535 holes"));
  holes.holes.pop_back();
  const StatusOr<VectorTileIdl> most = ToIdl(TileWith({}, {holes}));
  ASSERT_TRUE(most.ok()) << most.status();
  EXPECT_EQ(most->free_polygon_rings(), std::vector<uint16_t>{65535});
}

TEST(VectorTileCodecTest, FromIdlRefusesArraysThatDoNotAgree) {
  const Polyline line{{At(0, 0), At(100, 0)}, false, Steps(4)};
  const Polyline speck{{At(7, 8)}, false, Steps(2)};
  const FreePolygon square{{At(0, 0), At(900, 0), At(900, 900), At(0, 900)}, {{At(5, 5)}}};
  const VectorTileIdl good = Encoded(TileWith({line, speck}, {square}));
  ASSERT_TRUE(FromIdl(good).ok());
  struct Case {
    const char* expect;
    std::function<void(VectorTileIdl&)> spoil;
  };
  const Case cases[] = {
      {"layout_version is 0, this fleetmap reads 4", [](auto& t) { t.layout_version(0); }},
      {"obstacle_x has 2 values but obstacle_y 3", [](auto& t) { t.obstacle_y().push_back(1); }},
      {"obstacle_sizes add up to 3 vertices but 2 are given",
       [](auto& t) { t.obstacle_sizes({3}); }},
      {"obstacle_sizes[0] is 1: a polyline has at least two vertices",
       [](auto& t) {
         t.obstacle_sizes({1, 1});
         t.obstacle_half_widths({4, 4});
       }},
      {"obstacle_sizes[0] is 0",
       [](auto& t) {
         t.obstacle_sizes({0, 2});
       }},
      {"obstacle_half_widths has 2 values for 1 polylines",
       [](auto& t) {
         t.obstacle_half_widths({4, 4});
       }},
      {"point_x has 1 values but point_y 0", [](auto& t) { t.point_y().clear(); }},
      {"point_half_widths has 2 values for 1 points",
       [](auto& t) {
         t.point_half_widths({2, 2});
       }},
      {"point_x value 30000 lies outside its tile", [](auto& t) { t.point_x({30000}); }},
      {"point_y value -2000 lies outside its tile", [](auto& t) { t.point_y({-2000}); }},
      {"obstacle_y value 17500 lies outside its tile",
       [](auto& t) {
         t.obstacle_y({0, 17500});
       }},
      {"free_x has 6 values but free_y 5", [](auto& t) { t.free_x().push_back(0); }},
      {"free_polygon_rings add up to 3 rings but 2 are given",
       [](auto& t) { t.free_polygon_rings({3}); }},
      {"a free polygon has no outer ring",
       [](auto& t) {
         t.free_polygon_rings({0, 2});
       }},
      {"free_ring_sizes add up to 6 vertices but 5 are given",
       [](auto& t) {
         t.free_ring_sizes({5, 1});
       }},
      {"a free ring has no vertex",
       [](auto& t) {
         t.free_ring_sizes({5, 0});
       }},
      {"free_y value 20000 lies outside its tile", [](auto& t) { t.free_y()[2] = 20000; }},
  };
  for (const Case& c : cases) {
    VectorTileIdl bad = good;
    c.spoil(bad);
    const StatusOr<VectorTileMessage> back = FromIdl(bad);
    EXPECT_EQ(back.status().code(), StatusCode::kInvalidArgument) << c.expect;
    EXPECT_THAT(back.status().message(), HasSubstr(c.expect));
  }
}

// Random arrays, mostly inconsistent and sometimes consistent: the decoder refuses or decodes,
// never reads past an array, and what it decodes holds exactly the vertices it was given.
TEST(VectorTileCodecTest, SeededRandomTilesNeverCrashTheDecoder) {
  std::mt19937 random(99);
  const auto small = [&](int limit) { return static_cast<int>(random() % (limit + 1)); };
  const auto coordinates = [&](int count) {
    std::vector<int16_t> values(count);
    for (auto& v : values) v = static_cast<int16_t>(small(17000) - 300);
    return values;
  };
  const auto counts = [&](int count, int limit) {
    std::vector<uint16_t> values(count);
    for (auto& v : values) v = static_cast<uint16_t>(small(limit));
    return values;
  };
  const auto bytes = [&](int count, int limit) {
    std::vector<uint8_t> values(count);
    for (auto& v : values) v = static_cast<uint8_t>(small(limit));
    return values;
  };
  const VectorTileIdl base = Encoded(TileWith({}));
  int decoded = 0;
  for (int round = 0; round < 20000; ++round) {
    VectorTileIdl tile = base;
    const int polylines = small(3);
    tile.obstacle_sizes(bytes(polylines, 5));
    const int vertices = small(12);
    tile.obstacle_x(coordinates(vertices));
    tile.obstacle_y(coordinates(small(1) == 0 ? vertices : small(12)));
    tile.obstacle_half_widths(bytes(small(1) == 0 ? polylines : small(3), 255));
    const int points = small(3);
    tile.point_x(coordinates(points));
    tile.point_y(coordinates(small(1) == 0 ? points : small(3)));
    tile.point_half_widths(bytes(small(1) == 0 ? 0 : small(3), 255));
    const int polygons = small(2);
    tile.free_polygon_rings(counts(polygons, 2));
    tile.free_ring_sizes(counts(small(3), 4));
    const int free_vertices = small(10);
    tile.free_x(coordinates(free_vertices));
    tile.free_y(coordinates(free_vertices));
    const StatusOr<VectorTileMessage> back = FromIdl(tile);
    if (!back.ok()) {
      EXPECT_EQ(back.status().code(), StatusCode::kInvalidArgument);
      continue;
    }
    ++decoded;
    size_t wire_vertices = 0;
    for (const Polyline& polyline : back->map.obstacles) {
      wire_vertices += polyline.points.size() + (polyline.closed ? 1 : 0);
    }
    EXPECT_EQ(wire_vertices, tile.obstacle_x().size() + tile.point_x().size());
    EXPECT_EQ(back->map.FreeVertexCount(), tile.free_x().size());
  }
  EXPECT_GT(decoded, 0);
  EXPECT_LT(decoded, 20000);
}

// Free space with square rooms whose one-cell walls the vectorizer draws as closed rings.
grid::OccupancyGrid Rooms() {
  grid::OccupancyGrid grid(80, 60, 0.05, Pose2{}, grid::kFreeValue);
  for (const int x0 : {5, 30, 50}) {
    vector_map::testing::FillRect(grid, x0, 10, x0 + 12, 22, grid::kOccupiedValue);
    vector_map::testing::FillRect(grid, x0 + 1, 11, x0 + 11, 21, grid::kFreeValue);
  }
  return grid;
}

// What the vectorizer makes of a floor plan, of closed rooms and of speckle (many point obstacles
// and small rings) comes back exactly, in wire order, half widths included (whole steps).
TEST(VectorTileCodecTest, VectorizerTilesRoundTrip) {
  size_t points = 0;
  size_t closed = 0;
  for (const grid::OccupancyGrid& grid : {vector_map::testing::FloorPlan(), Rooms(),
                                          vector_map::testing::NoiseGrid(150, 120, 0.08, 7)}) {
    vector_map::TiledVectorizeOptions options;
    options.tile_size = 2.0;
    const StatusOr<vector_map::TiledVectorMap> tiled =
        vector_map::VectorizeTiled(grid, Transform2::Identity(), options);
    ASSERT_TRUE(tiled.ok()) << tiled.status();
    for (const auto& [id, map] : tiled->tiles) {
      VectorTileMessage message;
      message.tile = id;
      message.tile_size = options.tile_size;
      message.map = map;
      const StatusOr<VectorTileIdl> idl = ToIdl(message);
      ASSERT_TRUE(idl.ok()) << idl.status();
      const StatusOr<VectorTileMessage> back = FromIdl(*idl);
      ASSERT_TRUE(back.ok()) << back.status();
      const std::vector<Polyline> expected = WireOrder(map.obstacles);
      ASSERT_EQ(back->map.obstacles.size(), expected.size()) << id;
      for (size_t k = 0; k < expected.size(); ++k) {
        const Polyline& sent = expected[k];
        const Polyline& got = back->map.obstacles[k];
        EXPECT_EQ(got.points, sent.points) << id << " obstacle " << k;
        EXPECT_EQ(got.closed, sent.closed) << id << " obstacle " << k;
        EXPECT_EQ(got.half_width, sent.half_width) << id << " obstacle " << k;
        // Never an open loop (it would come back closed).
        if (!sent.closed && sent.points.size() >= 4) {
          EXPECT_NE(sent.points.front(), sent.points.back()) << id << " obstacle " << k;
        }
        if (sent.points.size() == 1) ++points;
        if (sent.closed) ++closed;
      }
      EXPECT_EQ(back->map.free_space, map.free_space) << id;
    }
  }
  // Both kinds the layout treats specially were exercised.
  EXPECT_GT(points, 10u);
  EXPECT_GT(closed, 0u);
}

}  // namespace
}  // namespace fleetmap::transport
