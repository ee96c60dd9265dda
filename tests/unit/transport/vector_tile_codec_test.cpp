// The VectorTile codec, layout 5 (docs/file-formats.md): round trips, seams, the varint edges,
// compression, and a decoder that refuses every kind of malformed tile without crashing.

#include "common/transport/internal/vector_tile_codec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <random>

#include "common/transport/internal/zstd_frame.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::transport {
namespace {

using ::testing::HasSubstr;
using vector_map::FreePolygon;
using vector_map::Polyline;
using VectorTileIdl = fleetmap_msgs::msg::dds_::VectorTile_;

constexpr double kTileSize = 10.0;
constexpr double kQuantum = 0.025;  // half a 5 cm cell
const TileId kTile{1, -2};
const Point2 kLatticeOrigin{0.0125, 0.005};  // within [0, kQuantum)

// The lattice point (i, j) steps from kTile's corner, computed as the decoder does.
Point2 At(int64_t i, int64_t j) {
  return {static_cast<double>(kTile.x * 400 + i) * kQuantum + kLatticeOrigin.x(),
          static_cast<double>(kTile.y * 400 + j) * kQuantum + kLatticeOrigin.y()};
}

// Whole half-width steps of the tiles' epsilon, as the vectorizer makes half widths.
double Steps(int n) { return n * vector_map::HalfWidthStep(0.0707); }

VectorTileMessage TileWith(std::vector<Polyline> obstacles, std::vector<FreePolygon> free = {}) {
  VectorTileMessage message;
  message.robot_id = RobotId{"alpha"};
  message.tile = kTile;
  message.tile_size = kTileSize;
  message.map.frame_id = "fleet";
  message.map.resolution = 0.05;
  message.map.epsilon = 0.0707;
  message.map.lattice = {kQuantum, kLatticeOrigin};
  message.map.obstacles = std::move(obstacles);
  message.map.free_space = std::move(free);
  return message;
}

VectorTileIdl Encoded(const VectorTileMessage& message) {
  StatusOr<VectorTileIdl> idl = ToIdl(message);
  EXPECT_TRUE(idl.ok()) << idl.status();
  return idl.ok() ? *std::move(idl) : VectorTileIdl();
}

vector_map::VectorMap Decoded(const VectorTileIdl& idl) {
  StatusOr<VectorTileMessage> back = FromIdl(idl);
  EXPECT_TRUE(back.ok()) << back.status();
  return back.ok() ? back->map : vector_map::VectorMap();
}

// The order FromIdl gives obstacles back in: polylines, then point obstacles, each as given.
std::vector<Polyline> WireOrder(std::vector<Polyline> obstacles) {
  std::stable_partition(obstacles.begin(), obstacles.end(),
                        [](const Polyline& p) { return p.points.size() != 1; });
  return obstacles;
}

// The plain geometry bytes of a tile (decompressed if need be).
std::vector<uint8_t> PlainGeometry(const VectorTileIdl& idl) {
  if (idl.compression() == 0) return idl.geometry();
  StatusOr<std::vector<uint8_t>> plain = ZstdDecompress(idl.geometry(), 1 << 22, "geometry");
  EXPECT_TRUE(plain.ok()) << plain.status();
  return plain.ok() ? *plain : std::vector<uint8_t>();
}

// The lattice that starts a geometry: the quantum's eight bytes, then the origin flag (and origin).
std::vector<uint8_t> LatticeBytes(double quantum, std::optional<Point2> origin = std::nullopt) {
  std::vector<uint8_t> bytes;
  const auto append = [&bytes](double value) {
    uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<uint8_t>(bits >> (8 * i)));
  };
  append(quantum);
  bytes.push_back(origin ? 1 : 0);
  if (origin) {
    append(origin->x());
    append(origin->y());
  }
  return bytes;
}

// `body` after the tiles' usual lattice (half-cell steps from the fleet origin).
std::vector<uint8_t> OnLattice(std::vector<uint8_t> body) {
  std::vector<uint8_t> bytes = LatticeBytes(kQuantum);
  bytes.insert(bytes.end(), body.begin(), body.end());
  return bytes;
}

// A tile whose geometry is `bytes` as they are, uncompressed.
VectorTileIdl WithGeometry(std::vector<uint8_t> bytes) {
  VectorTileIdl idl = Encoded(TileWith({}));
  idl.compression(0);
  idl.geometry(std::move(bytes));
  return idl;
}

void ExpectSamePoints(const std::vector<Point2>& got, const std::vector<Point2>& sent,
                      const std::string& where) {
  ASSERT_EQ(got.size(), sent.size()) << where;
  for (size_t i = 0; i < sent.size(); ++i) {
    EXPECT_NEAR(got[i].x(), sent[i].x(), 1e-9) << where << " vertex " << i;
    EXPECT_NEAR(got[i].y(), sent[i].y(), 1e-9) << where << " vertex " << i;
  }
}

// Every vertex, half width and ring of `sent` comes back from the wire (to float noise).
void ExpectSameMap(const vector_map::VectorMap& got, const vector_map::VectorMap& sent,
                   const std::string& where) {
  const std::vector<Polyline> expected = WireOrder(sent.obstacles);
  ASSERT_EQ(got.obstacles.size(), expected.size()) << where;
  for (size_t k = 0; k < expected.size(); ++k) {
    const std::string which = where + " obstacle " + std::to_string(k);
    ExpectSamePoints(got.obstacles[k].points, expected[k].points, which);
    EXPECT_EQ(got.obstacles[k].closed, expected[k].closed && expected[k].points.size() >= 3)
        << which;
    EXPECT_EQ(got.obstacles[k].half_width, expected[k].half_width) << which;
  }
  ASSERT_EQ(got.free_space.size(), sent.free_space.size()) << where;
  for (size_t k = 0; k < sent.free_space.size(); ++k) {
    const std::string which = where + " polygon " + std::to_string(k);
    ExpectSamePoints(got.free_space[k].outer, sent.free_space[k].outer, which);
    ASSERT_EQ(got.free_space[k].holes.size(), sent.free_space[k].holes.size()) << which;
    for (size_t h = 0; h < sent.free_space[k].holes.size(); ++h) {
      ExpectSamePoints(got.free_space[k].holes[h], sent.free_space[k].holes[h], which);
    }
  }
}

TEST(VectorTileCodecTest, EveryKindOfElementRoundTripsOnTheLattice) {
  const Polyline wall{{At(0, 0), At(100, 0), At(100, 37)}, false, Steps(120)};
  const Polyline room{{At(10, 10), At(20, 10), At(20, 20), At(10, 20)}, true, 0.0};
  const Polyline speck{{At(7, 8)}, false, 0.0};
  const Polyline fat_speck{{At(9, 10)}, false, Steps(41)};
  const FreePolygon free{{At(0, 0), At(400, 0), At(400, 400), At(0, 400)},
                         {{At(50, 50), At(60, 50), At(60, 60)}, {At(200, 200)}}};
  const VectorTileMessage message = TileWith({wall, speck, room, fat_speck}, {free});
  const VectorTileIdl idl = Encoded(message);
  EXPECT_EQ(idl.layout_version(), 5);
  EXPECT_EQ(idl.tile_size_mm(), 10000u);
  // The geometry starts with the lattice: quantum, origin flag 1, origin.
  const std::vector<uint8_t> plain = PlainGeometry(idl);
  ASSERT_GE(plain.size(), 25u);
  EXPECT_EQ(std::vector<uint8_t>(plain.begin(), plain.begin() + 25),
            LatticeBytes(kQuantum, kLatticeOrigin));
  const StatusOr<VectorTileMessage> back = FromIdl(idl);
  ASSERT_TRUE(back.ok()) << back.status();
  ExpectSameMap(back->map, message.map, "tile");
  EXPECT_EQ(back->map.obstacles[1].closed, true);
  EXPECT_EQ(back->tile_size, kTileSize);
  EXPECT_EQ(back->robot_id.value, "alpha");
  EXPECT_EQ(back->map.lattice.quantum, kQuantum);
  EXPECT_NEAR(back->map.lattice.origin.x(), kLatticeOrigin.x(), 1e-9);
}

TEST(VectorTileCodecTest, AnEmptyTileIsItsLatticeAndThreeZeros) {
  const VectorTileIdl idl = Encoded(TileWith({}));
  EXPECT_EQ(idl.compression(), 0);
  std::vector<uint8_t> expected = LatticeBytes(kQuantum, kLatticeOrigin);
  expected.insert(expected.end(), {0, 0, 0});
  EXPECT_EQ(idl.geometry(), expected);
  // The origin (0, 0), most maps' origin, costs one byte: 8 + 1 + 3.
  VectorTileMessage at_fleet_origin = TileWith({});
  at_fleet_origin.map.lattice.origin = Point2::Zero();
  EXPECT_EQ(Encoded(at_fleet_origin).geometry(), OnLattice({0, 0, 0}));
  const vector_map::VectorMap back = Decoded(idl);
  EXPECT_TRUE(back.obstacles.empty());
  EXPECT_TRUE(back.free_space.empty());
}

TEST(VectorTileCodecTest, AStepCostsOneByteUpTo63AndTwoAcrossTheTile) {
  // The second vertex's x step alone (zigzag: 63 -> 126, one byte; 64 -> 128, two; -64 -> 127,
  // one); a 10 m tile of 5 cm cells is 400 steps, so no step inside it takes three bytes.
  const auto x_step_bytes = [](int step) {
    const int from = step > 0 ? 0 : 400;
    const VectorTileMessage message =
        TileWith({Polyline{{At(from, 200), At(from + step, 200)}, false, 0.0}});
    const VectorTileIdl idl = Encoded(message);
    EXPECT_EQ(idl.compression(), 0);
    ExpectSameMap(Decoded(idl), message.map, "step " + std::to_string(step));
    return static_cast<int>(idl.geometry().size());
  };
  const int one_byte = x_step_bytes(1);
  EXPECT_EQ(x_step_bytes(63), one_byte);
  EXPECT_EQ(x_step_bytes(64), one_byte + 1);
  EXPECT_EQ(x_step_bytes(-64), x_step_bytes(-1));
  EXPECT_EQ(x_step_bytes(-65), x_step_bytes(-1) + 1);
  EXPECT_EQ(x_step_bytes(400), one_byte + 1);
  EXPECT_EQ(x_step_bytes(-400), x_step_bytes(-1) + 1);
}

TEST(VectorTileCodecTest, VerticesOnSharedBordersDecodeToTheSamePointFromBothTiles) {
  // Tiles (1, -2) and (2, -2) share the border x = 20 m (+ origin); (1, -1) shares y = -10 m.
  const Point2 east = At(400, 123);
  const Point2 north = At(321, 400);
  const Point2 corner = At(400, 400);
  VectorTileMessage west_tile = TileWith({Polyline{{At(0, 0), east, corner, north}, false, 0.0}});
  VectorTileMessage east_tile = TileWith({Polyline{{east, corner, At(700, 300)}, false, 0.0}});
  east_tile.tile = {kTile.x + 1, kTile.y};
  VectorTileMessage north_tile = TileWith({Polyline{{north, corner, At(350, 700)}, false, 0.0}});
  north_tile.tile = {kTile.x, kTile.y + 1};
  // All four borders of one tile carry vertices, and a vertex on each corner.
  VectorTileMessage all_borders = TileWith({Polyline{
      {At(0, 0), At(400, 0), At(400, 400), At(0, 400), At(0, 17), At(17, 0)}, true, 0.0}});
  const vector_map::VectorMap west = Decoded(Encoded(west_tile));
  const vector_map::VectorMap east_back = Decoded(Encoded(east_tile));
  const vector_map::VectorMap north_back = Decoded(Encoded(north_tile));
  ASSERT_EQ(west.obstacles.size(), 1u);
  ASSERT_EQ(east_back.obstacles.size(), 1u);
  ASSERT_EQ(north_back.obstacles.size(), 1u);
  // Bit for bit, not just close.
  EXPECT_EQ(west.obstacles[0].points[1], east_back.obstacles[0].points[0]);
  EXPECT_EQ(west.obstacles[0].points[2], east_back.obstacles[0].points[1]);
  EXPECT_EQ(west.obstacles[0].points[3], north_back.obstacles[0].points[0]);
  EXPECT_EQ(west.obstacles[0].points[2], north_back.obstacles[0].points[1]);
  ExpectSameMap(Decoded(Encoded(all_borders)), all_borders.map, "all borders");
}

TEST(VectorTileCodecTest, TheLongestPolylineTravelsWhole) {
  // A ragged wall along the whole tile and back, 20 000 vertices: one polyline, no pieces.
  Polyline wall;
  for (int i = 0; i < 20000; ++i) wall.points.push_back(At((i * 7) % 400, (i / 57) % 400));
  const VectorTileMessage message = TileWith({wall});
  const vector_map::VectorMap back = Decoded(Encoded(message));
  ExpectSameMap(back, message.map, "long wall");
}

TEST(VectorTileCodecTest, GeometryIsCompressedOnlyWhenThatIsSmaller) {
  std::vector<Polyline> walls;
  for (int i = 0; i < 200; ++i) {
    walls.push_back(Polyline{{At(10, i), At(20, i), At(30, i + 1)}, false, Steps(50)});
  }
  const VectorTileMessage repetitive = TileWith(walls);
  const VectorTileIdl compressed = Encoded(repetitive);
  EXPECT_EQ(compressed.compression(), 1);
  EXPECT_LT(compressed.geometry().size(), PlainGeometry(compressed).size());
  ExpectSameMap(Decoded(compressed), repetitive.map, "compressed");
  const VectorTileIdl small = Encoded(TileWith({Polyline{{At(1, 1), At(5, 3)}, false, 0.0}}));
  EXPECT_EQ(small.compression(), 0);
}

TEST(VectorTileCodecTest, AMapWithoutLatticeIsSentOnHalfCellStepsFromTheFleetOrigin) {
  VectorTileMessage message = TileWith({Polyline{{{10.012, -19.99}, {11.0, -19.0}}, false, 0.0}});
  message.map.lattice = {};
  const VectorTileIdl idl = Encoded(message);
  const vector_map::VectorMap back = Decoded(idl);
  EXPECT_EQ(back.lattice.quantum, 0.025);
  EXPECT_EQ(back.lattice.origin, Point2::Zero());
  ASSERT_EQ(back.obstacles.size(), 1u);
  EXPECT_NEAR(back.obstacles[0].points[0].x(), 10.0, 1e-12);  // rounded onto the lattice
  EXPECT_NEAR(back.obstacles[0].points[0].y(), -20.0, 1e-12);
}

TEST(VectorTileCodecTest, HalfWidthsTravelAsStepsOfEpsilonAndEpsilonAlwaysFits) {
  for (const double epsilon : {0.0707, 0.07071067811865477, 0.1414213562373095, 0.0353553, 0.3}) {
    VectorTileMessage message = TileWith({Polyline{{At(0, 0), At(100, 0)}, false, epsilon}});
    message.map.epsilon = epsilon;
    const vector_map::VectorMap back = Decoded(Encoded(message));
    ASSERT_EQ(back.obstacles.size(), 1u);
    EXPECT_GE(back.obstacles[0].half_width, epsilon) << epsilon;
    EXPECT_LT(back.obstacles[0].half_width, epsilon * 1.005) << epsilon;
    message.map.obstacles[0].half_width = epsilon * 1.01;
    EXPECT_THAT(ToIdl(message).status().message(), HasSubstr("is not within epsilon"));
  }
}

// Found by fuzz/tile_payload_fuzzer.cpp: fastcdr writes a string up to its first NUL, so such an
// id would come back as another one.
TEST(VectorTileCodecTest, RefusesARobotIdHoldingANul) {
  VectorTileIdl idl = Encoded(TileWith({}));
  idl.robot_id(std::string("al\0pha", 6));
  EXPECT_THAT(FromIdl(idl).status().message(), HasSubstr("NUL"));
}

TEST(VectorTileCodecTest, WhatCannotTravelIsRefusedByTheWriter) {
  VectorTileMessage far = TileWith({Polyline{{At(0, 0), At(2000, 0)}, false, 0.0}});
  EXPECT_THAT(ToIdl(far).status().message(), HasSubstr("lies outside its tile"));
  VectorTileMessage odd_size = TileWith({});
  odd_size.tile_size = 10.0001234;
  EXPECT_THAT(ToIdl(odd_size).status().message(), HasSubstr("whole number of millimetres"));
  VectorTileMessage no_quantum = TileWith({});
  no_quantum.map.lattice.quantum = 1e-9;
  EXPECT_THAT(ToIdl(no_quantum).status().message(), HasSubstr("steps of a"));
  VectorTileMessage nan = TileWith({Polyline{{At(0, 0), {std::nan(""), 0.0}}, false, 0.0}});
  EXPECT_FALSE(ToIdl(nan).ok());
}

// What the vectorizer makes of real SLAM maps, tile by tile, comes back vertex for vertex.
TEST(VectorTileCodecTest, RealMapTilesRoundTrip) {
  size_t maps = 0;
  for (const std::string& name : vector_map::testing::RealMapNames()) {
    grid::OccupancyGrid grid;
    if (!vector_map::testing::LoadRealMap(name, grid)) continue;
    ++maps;
    // A fleet frame that puts the grid's corner off the half-cell lattice of the fleet origin.
    const Transform2 fleet_from_map = Transform2::Identity();
    const StatusOr<vector_map::TiledVectorMap> tiled =
        vector_map::VectorizeTiled(grid, fleet_from_map, {});
    ASSERT_TRUE(tiled.ok()) << name << ": " << tiled.status();
    for (const auto& [id, map] : tiled->tiles) {
      VectorTileMessage message;
      message.tile = id;
      message.map = map;
      const std::string where =
          name + " tile (" + std::to_string(id.x) + ", " + std::to_string(id.y) + ")";
      const StatusOr<VectorTileIdl> idl = ToIdl(message);
      ASSERT_TRUE(idl.ok()) << where << ": " << idl.status();
      const StatusOr<VectorTileMessage> back = FromIdl(*idl);
      ASSERT_TRUE(back.ok()) << where << ": " << back.status();
      ExpectSameMap(back->map, map, where);
    }
  }
  EXPECT_GE(maps, 3u);
}

TEST(VectorTileCodecTest, MalformedHeadersAreRefusedByName) {
  const VectorTileIdl good = Encoded(TileWith({Polyline{{At(0, 0), At(10, 0)}, false, 0.0}}));
  const std::vector<std::pair<std::string, std::function<void(VectorTileIdl&)>>> cases = {
      {"layout_version is 6 (layouts 3 and 4 read so), this fleetmap reads 5",
       [](auto& t) { t.layout_version(6); }},
      {"layout_version is 0", [](auto& t) { t.layout_version(0); }},
      {"compression 7 is neither", [](auto& t) { t.compression(7); }},
      {"tile_size_mm is 0", [](auto& t) { t.tile_size_mm(0); }},
      {"epsilon nan", [](auto& t) { t.epsilon(std::nanf("")); }},
      {"resolution -0.05", [](auto& t) { t.resolution(-0.05f); }},
      {"the geometry is not a zstd frame", [](auto& t) { t.compression(1); }},
  };
  for (const auto& [message, breaker] : cases) {
    VectorTileIdl broken = good;
    breaker(broken);
    const StatusOr<VectorTileMessage> back = FromIdl(broken);
    ASSERT_FALSE(back.ok()) << message;
    EXPECT_THAT(back.status().message(), HasSubstr(message));
  }
}

TEST(VectorTileCodecTest, MalformedGeometryIsRefusedWithoutAllocatingWhatItClaims) {
  const std::vector<std::pair<std::string, std::vector<uint8_t>>> cases = {
      {"the lattice quantum is cut off: the geometry ends at byte 0", {}},
      {"quantum 0.000000 m", LatticeBytes(0.0)},
      {"quantum nan", LatticeBytes(std::nan(""))},
      {"quantum -0.025", LatticeBytes(-0.025)},
      {"quantum 20.000000 m", LatticeBytes(20.0)},
      {"the lattice origin flag is 2, neither 0 nor 1",
       [] {
         std::vector<uint8_t> bytes = LatticeBytes(kQuantum);
         bytes.back() = 2;
         return bytes;
       }()},
      {"lattice origin 0.030000 m is not within", LatticeBytes(kQuantum, Point2(0.03, 0.0))},
      {"lattice origin -0.001", LatticeBytes(kQuantum, Point2(0.0, -0.001))},
      {"lattice origin nan", LatticeBytes(kQuantum, Point2(0.0, std::nan("")))},
      {"the polyline count is cut off: the geometry ends at byte 9", OnLattice({})},
      {"the polyline count is 4294967295, more than the 2 bytes left",
       OnLattice({0xff, 0xff, 0xff, 0xff, 0x0f, 0, 0})},
      {"is a varint of more than 64 bits",
       OnLattice({0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01})},
      {"is a varint of more than 64 bits",
       OnLattice({0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x02})},
      // One polyline claiming 2^31 vertices.
      {"more than the", OnLattice({1, 0xfe, 0xff, 0xff, 0xff, 0x0f, 0, 2, 2, 2, 2})},
      {"is closed with 2 vertices", OnLattice({1, 1, 0, 2, 2, 2, 2, 0, 0})},
      // A vertex near the fleet origin, far from the tile.
      {"outside its tile", OnLattice({1, 0, 0, 2, 2, 2, 2, 0, 0})},
      {"a free polygon has no outer ring", OnLattice({0, 0, 1, 0, 0, 0, 0})},
      {"a free ring has no vertex", OnLattice({0, 0, 1, 1, 0, 0, 0})},
      {"bytes after its last polygon", OnLattice({0, 0, 0, 0})},
  };
  for (const auto& [message, bytes] : cases) {
    const StatusOr<VectorTileMessage> back = FromIdl(WithGeometry(bytes));
    ASSERT_FALSE(back.ok()) << message;
    EXPECT_THAT(back.status().message(), HasSubstr(message));
  }
  // A zstd frame that claims to inflate to more than any tile holds is refused before inflating.
  std::vector<uint8_t> zeros(size_t{5} << 20, 0);
  VectorTileIdl bomb = WithGeometry(ZstdCompress(zeros, 1));
  bomb.compression(1);
  EXPECT_THAT(FromIdl(bomb).status().message(), HasSubstr("more than the"));
}

TEST(VectorTileCodecTest, EveryTruncationAndByteFlipIsAnErrorOrAValidTileNeverACrash) {
  std::vector<Polyline> walls;
  for (int i = 0; i < 30; ++i) {
    walls.push_back(
        Polyline{{At(10 + i, 20), At(40, 20 + 3 * i), At(45 + i, 90)}, i % 2 == 0, Steps(i)});
  }
  walls.push_back(Polyline{{At(3, 3)}, false, Steps(9)});
  const FreePolygon free{{At(0, 0), At(400, 0), At(400, 400)}, {{At(50, 50), At(60, 55)}}};
  const VectorTileIdl idl = Encoded(TileWith(walls, {free}));
  const std::vector<uint8_t> plain = PlainGeometry(idl);
  for (size_t length = 0; length < plain.size(); ++length) {
    const std::vector<uint8_t> cut(plain.begin(), plain.begin() + length);
    EXPECT_FALSE(FromIdl(WithGeometry(cut)).ok()) << "cut at " << length;
  }
  std::mt19937 random(17);
  size_t refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<uint8_t> flipped = plain;
    flipped[random() % flipped.size()] ^= static_cast<uint8_t>(1 + random() % 255);
    if (!FromIdl(WithGeometry(flipped)).ok()) ++refused;
  }
  EXPECT_GT(refused, 100u);  // most flips break a count or a coordinate; none crashes
  // The same for the compressed form.
  VectorTileIdl compressed = idl;
  compressed.geometry(ZstdCompress(plain, 3));
  compressed.compression(1);
  EXPECT_TRUE(FromIdl(compressed).ok());
  for (size_t length = 0; length < compressed.geometry().size(); ++length) {
    VectorTileIdl cut = compressed;
    cut.geometry().resize(length);
    EXPECT_FALSE(FromIdl(cut).ok()) << "compressed, cut at " << length;
  }
}

}  // namespace
}  // namespace fleetmap::transport

namespace fleetmap::transport {
namespace {

// A zstd bomb as the probe sent it: a few KB on the wire, a million vertices decoded.
VectorTileIdl ZstdBomb(size_t vertices) {
  std::vector<Point2> ring;
  ring.reserve(vertices);
  for (size_t i = 0; i < vertices; ++i) ring.push_back(At(i % 2 == 0 ? 10 : 11, 10));
  VectorTileIdl idl = Encoded(TileWith({}, {FreePolygon{std::move(ring), {}}}));
  EXPECT_EQ(idl.compression(), 1);
  return idl;
}

TEST(VectorTileCodecTest, AZstdBombIsRefusedByItsStatedSizeBeforeItIsInflated) {
  const VectorTileIdl bomb = ZstdBomb(1'000'000);
  EXPECT_LT(bomb.geometry().size(), 64u << 10);  // a few KB that inflate to megabytes
  TileDecodeLimits limits;
  limits.max_geometry_bytes = 256 << 10;
  const StatusOr<VectorTileMessage> back = FromIdl(bomb, limits);
  ASSERT_FALSE(back.ok());
  // The frame's stated size is refused: nothing of that size was allocated.
  EXPECT_THAT(back.status().message(), HasSubstr("would decompress to"));
  EXPECT_THAT(back.status().message(), HasSubstr("more than the 262144 allowed"));
  // Without the server's limits the same tile decodes (files and stores hold such tiles).
  EXPECT_TRUE(FromIdl(bomb).ok());
}

TEST(VectorTileCodecTest, VerticesAndRingsPastTheLimitsAreRefusedBeforeTheyAreReserved) {
  const VectorTileIdl many = ZstdBomb(40'000);
  TileDecodeLimits limits;
  limits.max_vertices = 32'768;
  const StatusOr<VectorTileMessage> back = FromIdl(many, limits);
  ASSERT_FALSE(back.ok());
  EXPECT_THAT(back.status().message(), HasSubstr("more than 32768 vertices"));
  limits.max_vertices = 40'000;
  EXPECT_TRUE(FromIdl(many, limits).ok());  // exactly at the limit

  std::vector<FreePolygon> rooms;
  for (int i = 0; i < 5; ++i) rooms.push_back(FreePolygon{{At(i, 0), At(i, 5), At(i + 1, 5)}, {}});
  TileDecodeLimits rings;
  rings.max_rings = 4;
  const StatusOr<VectorTileMessage> five = FromIdl(Encoded(TileWith({}, rooms)), rings);
  ASSERT_FALSE(five.ok());
  EXPECT_THAT(five.status().message(), HasSubstr("more than 4 free rings"));
}

}  // namespace
}  // namespace fleetmap::transport
