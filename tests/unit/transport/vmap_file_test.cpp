#include "common/transport/vmap_file.hpp"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>

namespace fleetmap::transport {
namespace {

using ::testing::HasSubstr;
using vector_map::FreePolygon;
using vector_map::Polyline;
using vector_map::TiledVectorMap;

// The lattice of the sample maps: half-cell steps of 5 cm cells from the fleet origin.
constexpr double kQuantum = 0.025;
const vector_map::VertexLattice kLattice{kQuantum, Point2::Zero()};

// A point of tile `tile` at (i, j) steps from its corner, computed as the decoder does: on the
// lattice, as vectorizers make them.
Point2 At(const TileId& tile, double tile_size, int i, int j) {
  const auto per_side = static_cast<int64_t>(std::lround(tile_size / kQuantum));
  return {static_cast<double>(tile.x * per_side + i) * kQuantum,
          static_cast<double>(tile.y * per_side + j) * kQuantum};
}

// Half widths of whole steps of epsilon 0.0707, as the vectorizer makes them on the tile lattice.
double Steps(int n) { return n * vector_map::HalfWidthStep(0.0707); }

// Every kind of geometry the layout has: open and closed polylines, point obstacles with and
// without a half width, polygons with and without holes, and a tile with obstacles only.
TiledVectorMap SampleMap() {
  TiledVectorMap map;
  map.tile_size = 10.0;
  map.resolution = 0.05;
  map.epsilon = 0.0707;
  map.lattice = kLattice;
  const TileId a{0, 0};
  const TileId b{-1, 2};
  vector_map::VectorMap& first = map.tiles[a];
  first.frame_id = "fleet";
  first.resolution = 0.05;
  first.epsilon = 0.0707;
  first.lattice = kLattice;
  first.obstacles.push_back(
      Polyline{{At(a, 10, 0, 0), At(a, 10, 100, 5), At(a, 10, 400, 225)}, false, Steps(180)});
  first.obstacles.push_back(Polyline{{At(a, 10, 7, 7)}, false, 0.0});  // a point obstacle
  first.obstacles.push_back(
      Polyline{{At(a, 10, 10, 10), At(a, 10, 20, 10), At(a, 10, 20, 20)}, true, Steps(90)});
  first.obstacles.push_back(Polyline{{At(a, 10, 300, 40)}, false, Steps(90)});
  first.free_space.push_back(
      FreePolygon{{At(a, 10, 0, 0), At(a, 10, 300, 0), At(a, 10, 300, 300), At(a, 10, 0, 300)},
                  {{At(a, 10, 10, 10), At(a, 10, 20, 10), At(a, 10, 20, 20)}}});
  first.free_space.push_back(FreePolygon{{At(a, 10, 200, 200)}, {}});  // a free speck
  vector_map::VectorMap& second = map.tiles[b];
  second.frame_id = "fleet";
  second.resolution = 0.05;
  second.epsilon = 0.0707;
  second.lattice = kLattice;
  second.obstacles.push_back(Polyline{{At(b, 10, -5, 0), At(b, 10, 406, 400)}, false, 0.0});
  return map;
}

// The order the decoder gives obstacles back in: polylines, then point obstacles.
std::vector<Polyline> WireOrder(std::vector<Polyline> obstacles) {
  std::stable_partition(obstacles.begin(), obstacles.end(),
                        [](const Polyline& p) { return p.points.size() != 1; });
  return obstacles;
}

std::string Encoded(const TiledVectorMap& map) {
  auto bytes = EncodeVmap(map);
  EXPECT_TRUE(bytes.ok()) << bytes.status();
  return bytes.ok() ? *bytes : std::string();
}

TEST(VmapFileTest, RoundTripIsExactOnTheLattice) {
  const TiledVectorMap map = SampleMap();
  const auto decoded = DecodeVmap(Encoded(map), "sample.vmap");
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_EQ(decoded->tile_size, 10.0);
  EXPECT_FLOAT_EQ(decoded->epsilon, 0.0707);
  ASSERT_EQ(decoded->tiles.size(), 2u);
  for (const auto& [id, tile] : map.tiles) {
    const auto& back = decoded->tiles.at(id);
    EXPECT_EQ(back.obstacles, WireOrder(tile.obstacles)) << id;
    EXPECT_EQ(back.free_space, tile.free_space) << id;
    EXPECT_EQ(back.lattice, kLattice) << id;
  }
}

TEST(VmapFileTest, HalfWidthsOffTheStepRoundUp) {
  TiledVectorMap map = SampleMap();
  auto& obstacles = map.tiles.at({0, 0}).obstacles;
  obstacles[0].half_width = 0.05;    // 179.6 steps
  obstacles[1].half_width = 0.025;   // a point: 89.8 steps
  obstacles[2].half_width = 0.0707;  // epsilon itself fits, whatever the float rounding
  const auto decoded = DecodeVmap(Encoded(map), "sample.vmap");
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  const auto& back = decoded->tiles.at({0, 0}).obstacles;
  const std::vector<Polyline> sent = WireOrder(obstacles);
  ASSERT_EQ(back.size(), sent.size());
  for (size_t k = 0; k < sent.size(); ++k) {
    EXPECT_EQ(back[k].points, sent[k].points);
    // Never thinner than what was sent, and less than a step thicker.
    EXPECT_GE(back[k].half_width, sent[k].half_width);
    EXPECT_LT(back[k].half_width, sent[k].half_width + vector_map::HalfWidthStep(0.0707));
  }
}

// The example of docs/file-formats.md (VectorTile, field by field), after the encapsulation.
std::string DocumentedExample() {
  const char* const fields[] = {
      "10 00 00 00 66 6c 65 65 74 6d 61 70 2d 76 6d 61 70 2f 35 00",  // format
      "06 00 00 00 66 6c 65 65 74 00",                                // frame_id
      "00 00",                                                        // padding
      "00 00 00 00 00 00 24 40",                                      // tile_size 10
      "29 cb 90 3d",                                                  // epsilon
      "cd cc 4c 3d",                                                  // resolution
      "01 00 00 00",                                                  // tiles: 1
      "01 00 00 00 00",                                               // robot_id ""
      "00 00 00",                                                     // padding
      "00 00 00 00",                                                  // tile_x 0
      "00 00 00 00",                                                  // tile_y 0
      "00 00 00 00",                                                  // stamp.sec
      "00 00 00 00",                                                  // stamp.nanosec
      "05",                                                           // layout_version
      "00",                                                           // compression: plain
      "00 00",                                                        // padding
      "00 00 00 00",                                                  // revision
      "10 27 00 00",                                                  // tile_size_mm 10000
      "29 cb 90 3d",                                                  // epsilon
      "cd cc 4c 3d",                                                  // resolution
      "30 00 00 00",                                                  // geometry: 48 bytes
      "9a 99 99 99 99 99 99 3f",                                      // quantum 0.025
      "00",                                                           // origin (0, 0)
      "02",                                                           // 2 polylines
      "00 b4 00 00 a0 06 00",                 // open, 2 vertices, half width 180: (0, 0) (400, 0)
      "03 00 d7 04 c8 01 c8 01 00 00 c8 01",  // closed, 3: (100, 100) (200, 100) (200, 200)
      "01",                                   // 1 point
      "00 64 ac 02",                          // half width 0: (250, 350)
      "01 01 03",                             // 1 polygon, 1 ring, 3 vertices
      "f3 03 bb 05 a0 06 00 9f 06 a0 06",     // (0, 0) (400, 0) (0, 400)
  };
  std::string bytes("\x00\x01\x00\x00", 4);
  for (const char* field : fields) {
    for (const char* hex = field; *hex != '\0'; hex += hex[2] == ' ' ? 3 : 2) {
      bytes.push_back(static_cast<char>(std::stoi(std::string(hex, 2), nullptr, 16)));
    }
  }
  return bytes;
}

TEST(VmapFileTest, TheDocumentedExampleIsWhatTheCodecWrites) {
  const TileId id{0, 0};
  TiledVectorMap map;
  map.epsilon = 0.0707;
  map.lattice = kLattice;
  vector_map::VectorMap& tile = map.tiles[id];
  tile.frame_id = "fleet";
  tile.epsilon = 0.0707;
  tile.lattice = kLattice;
  tile.obstacles = {
      Polyline{{At(id, 10, 0, 0), At(id, 10, 400, 0)}, false, Steps(180)},
      Polyline{{At(id, 10, 100, 100), At(id, 10, 200, 100), At(id, 10, 200, 200)}, true, 0.0},
      Polyline{{At(id, 10, 250, 350)}, false, 0.0}};
  tile.free_space = {FreePolygon{{At(id, 10, 0, 0), At(id, 10, 400, 0), At(id, 10, 0, 400)}, {}}};
  const std::string documented = DocumentedExample();
  ASSERT_EQ(documented.size(), 152u);
  EXPECT_EQ(Encoded(map), documented);
  const auto decoded = DecodeVmap(documented, "example.vmap");
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_EQ(decoded->tiles.at(id).obstacles, tile.obstacles);
  EXPECT_EQ(decoded->tiles.at(id).free_space, tile.free_space);
}

TEST(VmapFileTest, BorderVertexIsTheSamePointFromBothTiles) {
  // x = 10 m is the right border of tile 0 and the left border of tile 1.
  const Point2 from_left = At(TileId{0, 0}, 10.0, 400, 123);
  const Point2 from_right = At(TileId{1, 0}, 10.0, 0, 123);
  EXPECT_EQ(from_left, from_right);
  TiledVectorMap map;
  map.epsilon = 0.0707;
  for (const TileId id : {TileId{0, 0}, TileId{1, 0}}) map.tiles[id].epsilon = map.epsilon;
  map.tiles[{0, 0}].obstacles.push_back(Polyline{{At({0, 0}, 10, 100, 123), from_left}});
  map.tiles[{1, 0}].obstacles.push_back(Polyline{{from_right, At({1, 0}, 10, 300, 123)}});
  const auto decoded = DecodeVmap(Encoded(map), "border.vmap");
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_EQ(decoded->tiles.at({0, 0}).obstacles[0].points.back(),
            decoded->tiles.at({1, 0}).obstacles[0].points.front());
}

TEST(VmapFileTest, FileRoundTripAndMissingFile) {
  const std::string path =
      ::testing::TempDir() + "/vmap_test_" + std::to_string(getpid()) + ".vmap";
  ASSERT_TRUE(WriteVmapFile(SampleMap(), path).ok());
  const auto read = ReadVmapFile(path);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->tiles.size(), 2u);
  EXPECT_THAT(ReadVmapFile(path, {.max_bytes = 10}).status().message(), HasSubstr("limit"));
  std::remove(path.c_str());
  const auto missing = ReadVmapFile(path);
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(missing.status().message(), HasSubstr(path));
}

TEST(VmapFileTest, RefusesVerticesOutsideTheirTile) {
  TiledVectorMap map;
  map.tiles[{0, 0}].epsilon = 0.07;
  map.tiles[{0, 0}].obstacles.push_back(Polyline{{Point2(0, 0), Point2(1e12, 0)}});
  EXPECT_THAT(EncodeVmap(map).status().message(), HasSubstr("outside its tile"));
  map.tiles[{0, 0}].obstacles[0].points[1] = Point2(11.0, 0);  // 1 m outside a 10 m tile
  EXPECT_THAT(EncodeVmap(map).status().message(), HasSubstr("outside its tile"));
  map.tiles[{0, 0}].obstacles[0].points[1] = Point2(10.0, 0);  // on the border: fine
  EXPECT_TRUE(EncodeVmap(map).ok());
  map.tiles[{0, 0}].epsilon = 0.0;
  EXPECT_THAT(EncodeVmap(map).status().message(), HasSubstr("epsilon"));
  map.tiles[{0, 0}].epsilon = 0.07;
  map.tiles[{0, 0}].obstacles[0].points[1] = Point2(std::nan(""), 0);
  EXPECT_FALSE(EncodeVmap(map).ok());
}

TEST(VmapFileTest, EveryTruncationIsAClearError) {
  const std::string bytes = Encoded(SampleMap());
  for (size_t length = 0; length < bytes.size(); ++length) {
    const auto decoded = DecodeVmap(std::string_view(bytes).substr(0, length), "cut.vmap");
    ASSERT_FALSE(decoded.ok()) << "a " << length << "-byte prefix decoded";
    EXPECT_THAT(decoded.status().message(), HasSubstr("cut.vmap"));
  }
}

TEST(VmapFileTest, RefusesOtherFormatsAndBadHeaders) {
  std::string bytes = Encoded(SampleMap());
  std::string other = bytes;
  other[1] = 7;  // encapsulation: not plain CDR
  EXPECT_THAT(DecodeVmap(other, "x.vmap").status().message(), HasSubstr("not a plain CDR"));
  other = bytes;
  other[4 + 4] = 'g';  // inside the format string "fleetmap-vmap/5"
  EXPECT_THAT(DecodeVmap(other, "x.vmap").status().message(),
              HasSubstr("x.vmap: format \"gleetmap-vmap/5\" is not fleetmap-vmap/5"));
  EXPECT_FALSE(DecodeVmap("hello world, not a map", "x.vmap").ok());
  // A format string longer than any version's, in a file larger than the bytes read for it.
  TiledVectorMap large = SampleMap();
  std::mt19937 random(5);  // scattered points, which zstd cannot squeeze below 2000 bytes
  for (int i = 0; i < 1000; ++i) {
    large.tiles.at({0, 0}).obstacles.push_back(Polyline{
        {At({0, 0}, 10, static_cast<int>(random() % 400), static_cast<int>(random() % 400))}});
  }
  other = Encoded(large);
  ASSERT_GT(other.size(), 2000u);
  other[4] = '\xd0';  // the format's length: 2000
  other[5] = '\x07';
  EXPECT_THAT(DecodeVmap(other, "x.vmap").status().message(),
              HasSubstr("x.vmap: not a valid .vmap: no format string in its first"));
}

TEST(VmapFileTest, RefusesLengthsThatClaimMoreThanTheFileHolds) {
  std::string bytes = Encoded(SampleMap());
  // The tiles sequence length sits after format, frame_id, tile_size, epsilon, resolution.
  // Rather than compute the offset, patch every aligned uint32 in turn to a huge count: each
  // patched file must be refused or decode to something sane, and never allocate gigabytes.
  for (size_t offset = 4; offset + 4 <= bytes.size(); offset += 4) {
    std::string patched = bytes;
    patched[offset] = '\xff';
    patched[offset + 1] = '\xff';
    patched[offset + 2] = '\xff';
    patched[offset + 3] = '\x7f';
    const auto decoded = DecodeVmap(patched, "patched.vmap");
    if (decoded.ok()) {
      EXPECT_LE(decoded->ObstacleVertexCount(), 100u);
    }
  }
}

TEST(VmapFileTest, RefusesCountsThatDoNotAddUp) {
  std::string bytes = DocumentedExample();
  // The geometry's first byte: 2 polylines. 3 would claim more than the bytes hold.
  const size_t polylines = 4 + 100 + 9;
  ASSERT_EQ(bytes[polylines], 2);
  bytes[polylines] = 3;
  EXPECT_THAT(DecodeVmap(bytes, "counts.vmap").status().message(),
              HasSubstr("counts.vmap: tile (0, 0): "));  // a point's half width where a vertex was
  bytes[polylines] = 100;
  EXPECT_THAT(DecodeVmap(bytes, "counts.vmap").status().message(),
              HasSubstr("the polyline count is 100, more than the 38 bytes left can hold"));
}

// A version 1 file, written as fleetmap-vmap/1 laid it out (uint32 counts, obstacle_closed flags,
// no point arrays): refused by name, before its layout is checked against the current version.
std::string VersionOneFile() {
  std::string bytes(512, '\0');
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS,
                             eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  cdr << std::string("fleetmap-vmap/1") << std::string("fleet") << 10.0 << 0.0707f << 0.05f;
  cdr << uint32_t{1};                                  // one tile
  cdr << std::string("") << int32_t{0} << int32_t{0};  // robot_id, tile_x, tile_y
  cdr << int32_t{0} << uint32_t{0};                    // stamp
  cdr << std::string("fleet") << uint32_t{0} << 10.0 << 10.0 / 16384 << 0.0707f << 0.05f;
  cdr << std::vector<uint32_t>{2} << std::vector<uint8_t>{0} << std::vector<uint16_t>{0};
  cdr << std::vector<int16_t>{0, 100} << std::vector<int16_t>{0, 0};
  cdr << std::vector<uint32_t>{} << std::vector<uint32_t>{} << std::vector<int16_t>{}
      << std::vector<int16_t>{};
  bytes.resize(cdr.getSerializedDataLength());
  return bytes;
}

TEST(VmapFileTest, AVersionOneFileIsRefusedNamingBothVersions) {
  const auto decoded = DecodeVmap(VersionOneFile(), "old.vmap");
  ASSERT_FALSE(decoded.ok());
  EXPECT_EQ(decoded.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(decoded.status().message(),
              HasSubstr("old.vmap: format fleetmap-vmap/1 is another version of the .vmap format; "
                        "this fleetmap reads fleetmap-vmap/5 only"));
  // From a file as well.
  const std::string path =
      ::testing::TempDir() + "/vmap_v1_test_" + std::to_string(getpid()) + ".vmap";
  {
    std::ofstream out(path, std::ios::binary);
    const std::string bytes = VersionOneFile();
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  EXPECT_THAT(ReadVmapFile(path).status().message(),
              HasSubstr(path + ": format fleetmap-vmap/1 is another version"));
  std::remove(path.c_str());
}

TEST(VmapFileTest, VersionTwoToFourFilesAreRefusedNamingBothVersions) {
  // Version 2 (quantum tile_size / 16384: coordinates 2.4 % off), version 3 (uint16 sizes and
  // half widths in quanta) and version 4 (int16 arrays) are refused by their format string,
  // before any tile is read.
  for (const char version : {'2', '3', '4'}) {
    std::string bytes = Encoded(SampleMap());
    const size_t at = bytes.find("fleetmap-vmap/5");
    ASSERT_NE(at, std::string::npos);
    bytes[at + std::string("fleetmap-vmap/").size()] = version;
    const auto decoded = DecodeVmap(bytes, "old.vmap");
    ASSERT_FALSE(decoded.ok());
    EXPECT_THAT(decoded.status().message(),
                HasSubstr(std::string("old.vmap: format fleetmap-vmap/") + version +
                          " is another version of the .vmap format; this fleetmap reads "
                          "fleetmap-vmap/5 only"));
  }
}

TEST(VmapFileTest, SeededMutationsNeverCrash) {
  const std::string bytes = Encoded(SampleMap());
  std::mt19937 random(1234);
  int decoded_ok = 0;
  for (int round = 0; round < 5000; ++round) {
    std::string mutated = bytes;
    const int edits = 1 + static_cast<int>(random() % 8);
    for (int e = 0; e < edits; ++e) {
      mutated[random() % mutated.size()] = static_cast<char>(random() & 0xff);
    }
    if (random() % 4 == 0) mutated.resize(random() % mutated.size());
    const auto decoded = DecodeVmap(mutated, "fuzz.vmap");
    if (decoded.ok()) {
      ++decoded_ok;
      EXPECT_TRUE(std::isfinite(decoded->tile_size));
    } else {
      EXPECT_THAT(decoded.status().message(), HasSubstr("fuzz.vmap"));
    }
  }
  // Most mutations of a small file hit coordinates and still decode: both paths were exercised.
  EXPECT_GT(decoded_ok, 0);
  EXPECT_LT(decoded_ok, 5000);
}

TEST(VmapFileTest, SeededMutationsOfTheGeometryNeverCrash) {
  // Byte edits only in the geometry of the documented example, where counts, half widths and
  // coordinate steps sit side by side; a quarter are random bytes, the rest flip one bit.
  const std::string bytes = DocumentedExample();
  const size_t geometry = 4 + 100;
  std::mt19937 random(4321);
  int decoded_ok = 0;
  for (int round = 0; round < 5000; ++round) {
    std::string mutated = bytes;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits; ++e) {
      const size_t at = geometry + random() % (mutated.size() - geometry);
      mutated[at] = static_cast<char>(random() % 4 == 0 ? random() & 0xff : mutated[at] ^ 1);
    }
    const auto decoded = DecodeVmap(mutated, "geometry.vmap");
    if (decoded.ok()) {
      ++decoded_ok;
      // Each vertex takes at least two bytes.
      EXPECT_LE(decoded->ObstacleVertexCount() + decoded->FreeVertexCount(), 48u / 2);
    } else {
      EXPECT_THAT(decoded.status().message(), HasSubstr("geometry.vmap"));
    }
  }
  EXPECT_GT(decoded_ok, 0);
  EXPECT_LT(decoded_ok, 5000);
}

}  // namespace
}  // namespace fleetmap::transport
