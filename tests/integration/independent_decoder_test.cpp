// Issue 17: the plain tile layout is readable from idl/ and docs/file-formats.md alone. The
// independent decoder tools/vmap_decode.py (Python standard library, written from the docs) reads
// the .vmap files fleetmap writes for the real maps, and what it reads must be what the C++ reader
// (transport::ReadVmapFile) reads: the same tiles, obstacles and free polygons, vertex for vertex.
// Skipped only when python3 or the zstd tool is missing.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/vmap_file.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "common/vector_map/vector_map.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/unit/vector_map/test_grids.hpp"

namespace fleetmap::transport {
namespace {

using nlohmann::json;

constexpr double kVertexTolerance = 1e-9;      // metres
constexpr double kHalfWidthTolerance = 1e-12;  // metres

const std::string kDecoder = std::string(FLEETMAP_SOURCE_DIR) + "/tools/vmap_decode.py";

// A fleet_from_map that is not a whole number of cells (nor of half cells) on either axis, so the
// lattice origin is neither 0 nor a value a decoder could guess.
Transform2 FleetFromMap() { return Pose2{3.2071, -1.0133, 0.0}.ToTransform(); }

// 2 m tiles: a small map still spans several.
vector_map::TiledVectorizeOptions SmallTiles() {
  vector_map::TiledVectorizeOptions options;
  options.tile_size = 2.0;
  return options;
}

// The executable `name` on PATH (Subprocess spawns without a PATH search), or "" if there is none.
std::string FindOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path == nullptr ? "" : path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

process::CommandResult RunDecoder(const std::string& python3, std::vector<std::string> args) {
  std::vector<std::string> argv = {python3, kDecoder};
  argv.insert(argv.end(), args.begin(), args.end());
  return process::RunCommand(std::move(argv), std::chrono::minutes(2));
}

std::string Where(const TileId& tile) {
  std::stringstream out;
  out << tile;  // "tile(x, y)"
  return out.str();
}

::testing::AssertionResult PointsAgree(const json& got, const std::vector<Point2>& expected,
                                       const std::string& where) {
  if (!got.is_array() || got.size() != expected.size()) {
    return ::testing::AssertionFailure()
           << where << ": the decoder gives " << (got.is_array() ? got.size() : 0)
           << " vertices, ReadVmapFile " << expected.size();
  }
  for (size_t v = 0; v < expected.size(); ++v) {
    const double x = got[v].at(0).get<double>(), y = got[v].at(1).get<double>();
    if (std::abs(x - expected[v].x()) > kVertexTolerance ||
        std::abs(y - expected[v].y()) > kVertexTolerance) {
      return ::testing::AssertionFailure()
             << where << " vertex " << v << ": the decoder gives (" << x << ", " << y
             << "), ReadVmapFile (" << expected[v].x() << ", " << expected[v].y() << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

// The first difference between one tile as the decoder prints it and as ReadVmapFile reads it.
::testing::AssertionResult TileAgrees(const json& got, const TileId& id,
                                      const vector_map::VectorMap& expected) {
  const std::string where = Where(id);
  if (got.at("quantum").get<double>() != expected.lattice.quantum ||
      got.at("lattice_x").get<double>() != expected.lattice.origin.x() ||
      got.at("lattice_y").get<double>() != expected.lattice.origin.y()) {
    return ::testing::AssertionFailure()
           << where << ": the decoder's lattice is " << got.at("quantum") << " from ("
           << got.at("lattice_x") << ", " << got.at("lattice_y") << "), ReadVmapFile's "
           << expected.lattice.quantum << " from (" << expected.lattice.origin.x() << ", "
           << expected.lattice.origin.y() << ")";
  }
  const json& obstacles = got.at("obstacles");
  if (obstacles.size() != expected.obstacles.size()) {
    return ::testing::AssertionFailure()
           << where << ": the decoder gives " << obstacles.size() << " obstacles, ReadVmapFile "
           << expected.obstacles.size();
  }
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const vector_map::Polyline& want = expected.obstacles[k];
    const std::string obstacle = where + " obstacle " + std::to_string(k);
    if (obstacles[k].at("closed").get<bool>() != want.closed) {
      return ::testing::AssertionFailure()
             << obstacle << ": the decoder says closed " << obstacles[k].at("closed")
             << ", ReadVmapFile " << want.closed;
    }
    const double half_width = obstacles[k].at("half_width").get<double>();
    if (std::abs(half_width - want.half_width) > kHalfWidthTolerance) {
      return ::testing::AssertionFailure() << obstacle << ": the decoder's half width is "
                                           << half_width << ", ReadVmapFile's " << want.half_width;
    }
    auto points = PointsAgree(obstacles[k].at("points"), want.points, obstacle);
    if (!points) return points;
  }
  const json& free_space = got.at("free_space");
  if (free_space.size() != expected.free_space.size()) {
    return ::testing::AssertionFailure()
           << where << ": the decoder gives " << free_space.size()
           << " free polygons, ReadVmapFile " << expected.free_space.size();
  }
  for (size_t k = 0; k < free_space.size(); ++k) {
    const vector_map::FreePolygon& want = expected.free_space[k];
    const std::string polygon = where + " free polygon " + std::to_string(k);
    auto outer = PointsAgree(free_space[k].at("outer"), want.outer, polygon + " outer ring");
    if (!outer) return outer;
    const json& holes = free_space[k].at("holes");
    if (holes.size() != want.holes.size()) {
      return ::testing::AssertionFailure() << polygon << ": the decoder gives " << holes.size()
                                           << " holes, ReadVmapFile " << want.holes.size();
    }
    for (size_t h = 0; h < holes.size(); ++h) {
      auto hole = PointsAgree(holes[h], want.holes[h], polygon + " hole " + std::to_string(h));
      if (!hole) return hole;
    }
  }
  return ::testing::AssertionSuccess();
}

// The header's float32 fields: the decoder widens the stored float to a double, ReadVmapFile
// reads it as the decimal it stands for (0.05F as 0.05); both are the same float32.
bool SameFloat32(const json& got, double want) {
  return static_cast<float>(got.get<double>()) == static_cast<float>(want);
}

// The decoder's JSON against ReadVmapFile's map, field by field; the first difference fails.
::testing::AssertionResult DecodedAgrees(const json& got, const vector_map::TiledVectorMap& want) {
  if (got.at("format") != "fleetmap-vmap/5" || got.at("frame_id") != want.frame_id ||
      !SameFloat32(got.at("tile_size"), want.tile_size) ||
      !SameFloat32(got.at("epsilon"), want.epsilon) ||
      !SameFloat32(got.at("resolution"), want.resolution)) {
    return ::testing::AssertionFailure()
           << "header: the decoder gives " << got.at("format") << " " << got.at("frame_id")
           << " tile_size " << got.at("tile_size") << " epsilon " << got.at("epsilon")
           << " resolution " << got.at("resolution") << "; ReadVmapFile " << want.frame_id
           << " tile_size " << want.tile_size << " epsilon " << want.epsilon << " resolution "
           << want.resolution;
  }
  const json& tiles = got.at("tiles");
  if (tiles.size() != want.tiles.size()) {
    return ::testing::AssertionFailure()
           << "the decoder gives " << tiles.size() << " tiles, ReadVmapFile " << want.tiles.size();
  }
  for (const json& tile : tiles) {
    const TileId id{tile.at("tile_x").get<int32_t>(), tile.at("tile_y").get<int32_t>()};
    const auto it = want.tiles.find(id);
    if (it == want.tiles.end()) {
      return ::testing::AssertionFailure()
             << "the decoder gives " << Where(id) << ", which ReadVmapFile does not";
    }
    auto agrees = TileAgrees(tile, id, it->second);
    if (!agrees) return agrees;
  }
  return ::testing::AssertionSuccess();
}

class IndependentDecoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string python3 = FindOnPath("python3");
    if (python3.empty()) GTEST_SKIP() << "python3 is not on PATH";
    if (FindOnPath("zstd").empty()) GTEST_SKIP() << "the zstd tool is not on PATH";
    // The interpreter itself rather than a launcher (a pyenv shim costs 0.4 s a run).
    const process::CommandResult which =
        process::RunCommand({python3, "-c", "import sys; print(sys.executable)"});
    ASSERT_EQ(which.exit_code, 0) << which.output();
    python3_ = which.out.substr(0, which.out.find('\n'));
    if (python3_.empty()) python3_ = python3;
  }

  // Writes `map` with WriteVmapFile and reads it back with ReadVmapFile.
  vector_map::TiledVectorMap WriteAndRead(const vector_map::TiledVectorMap& map,
                                          const std::string& path) {
    const Status written = WriteVmapFile(map, path);
    EXPECT_TRUE(written.ok()) << written;
    auto read = ReadVmapFile(path);
    EXPECT_TRUE(read.ok()) << read.status();
    return read.ok() ? *read : vector_map::TiledVectorMap{};
  }

  std::string python3_;
  fleetmap::testing::ScratchDir dir_{"independent_decoder"};
};

TEST_F(IndependentDecoderTest, DecodesEveryRealMapAsTheCppReaderDoes) {
  int maps = 0;
  int maps_with_compressed_tiles = 0;
  // Every kind of element the layout has must occur somewhere, or its decoding went untested.
  int closed = 0, points = 0, thick = 0, holes = 0;
  for (const std::string& name : vector_map::testing::RealMapNames()) {
    grid::OccupancyGrid grid;
    if (!vector_map::testing::LoadRealMap(name, grid)) continue;
    SCOPED_TRACE(name);
    ++maps;
    auto map = vector_map::VectorizeTiled(grid, FleetFromMap());
    ASSERT_TRUE(map.ok()) << map.status();
    const std::string path = dir_.Path(name + ".vmap");
    const vector_map::TiledVectorMap want = WriteAndRead(*map, path);
    ASSERT_FALSE(want.tiles.empty());
    ASSERT_GT(want.ObstacleVertexCount(), 0u);
    ASSERT_GT(want.FreeVertexCount(), 0u);
    for (const auto& [id, tile] : want.tiles) {
      for (const vector_map::Polyline& obstacle : tile.obstacles) {
        closed += obstacle.closed ? 1 : 0;
        points += obstacle.points.size() == 1 ? 1 : 0;
        thick += obstacle.half_width > 0.0 ? 1 : 0;
      }
      for (const vector_map::FreePolygon& polygon : tile.free_space) {
        holes += static_cast<int>(polygon.holes.size());
      }
    }
    // The lattice origin must matter: a decoder that left it out would be off by it.
    const Point2 origin = want.tiles.begin()->second.lattice.origin;
    ASSERT_GT(std::abs(origin.x()), 100 * kVertexTolerance);
    ASSERT_GT(std::abs(origin.y()), 100 * kVertexTolerance);

    const process::CommandResult result = RunDecoder(python3_, {path});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const json got = json::parse(result.out, nullptr, /*allow_exceptions=*/false);
    ASSERT_FALSE(got.is_discarded()) << "not JSON: " << result.out.substr(0, 200);
    EXPECT_TRUE(DecodedAgrees(got, want));

    // Without zstd the decoder refuses compressed tiles by name (exit 1), and the real maps must
    // have some, or the zstd path above went untested.
    const process::CommandResult plain_only = RunDecoder(python3_, {"--no-zstd", path});
    if (plain_only.exit_code != 0) {
      EXPECT_EQ(plain_only.exit_code, 1) << plain_only.err;
      EXPECT_NE(plain_only.err.find("compressed"), std::string::npos) << plain_only.err;
      EXPECT_NE(plain_only.err.find(path), std::string::npos) << plain_only.err;
      ++maps_with_compressed_tiles;
    }
  }
  ASSERT_GT(maps, 0) << "no real map in " << FLEETMAP_SHARED_MAPS_DIR;
  EXPECT_GT(maps_with_compressed_tiles, 0) << "no map has a zstd-compressed tile";
  EXPECT_GT(closed, 0);
  EXPECT_GT(points, 0);
  EXPECT_GT(thick, 0);
  EXPECT_GT(holes, 0);
}

// A room a metre across in 0.5 m tiles (a wall, a pillar, a speck, free space with a hole):
// tiles too small to be worth compressing, so plain geometry only, decoded without the zstd tool
// and written to a file with -o.
TEST_F(IndependentDecoderTest, DecodesPlainTilesWithoutZstd) {
  const grid::OccupancyGrid grid = vector_map::testing::GridFromPicture({
      "??????????????????????",
      "?####################?",
      "?#..................#?",
      "?#..................#?",
      "?#....###...........#?",
      "?#....###......#....#?",
      "?#....###...........#?",
      "?#..................#?",
      "?#.........??.......#?",
      "?#.........??.......#?",
      "?#..................#?",
      "?####################?",
  });
  vector_map::TiledVectorizeOptions options;
  options.tile_size = 0.5;
  auto map = vector_map::VectorizeTiled(grid, FleetFromMap(), options);
  ASSERT_TRUE(map.ok()) << map.status();
  const std::string path = dir_.Path("room.vmap");
  const vector_map::TiledVectorMap want = WriteAndRead(*map, path);
  ASSERT_GT(want.tiles.size(), 1u);
  ASSERT_GT(want.ObstacleVertexCount(), 0u);
  ASSERT_GT(want.FreeVertexCount(), 0u);

  const std::string out = dir_.Path("room.json");
  const process::CommandResult result = RunDecoder(python3_, {"--no-zstd", path, "-o", out});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out, "");
  const json got = json::parse(fleetmap::testing::ReadFile(out), nullptr, false);
  ASSERT_FALSE(got.is_discarded());
  EXPECT_TRUE(DecodedAgrees(got, want));
}

// Every truncation of a real .vmap, and bytes overwritten in it, give exit 2 with a message naming
// the file (or, for an overwrite the format allows, a decoded map): never a Python traceback.
TEST_F(IndependentDecoderTest, MalformedFilesAreRefusedByName) {
  const grid::OccupancyGrid grid = vector_map::testing::FloorPlan();
  auto map = vector_map::VectorizeTiled(grid, FleetFromMap(), SmallTiles());
  ASSERT_TRUE(map.ok()) << map.status();
  const std::string good_path = dir_.Path("good.vmap");
  ASSERT_TRUE(WriteVmapFile(*map, good_path).ok());
  const std::string good = fleetmap::testing::ReadFile(good_path);
  ASSERT_GT(good.size(), 64u);

  const std::string bad_path = dir_.Path("bad.vmap");
  auto run_on = [&](const std::string& bytes) {
    std::ofstream(bad_path, std::ios::binary | std::ios::trunc) << bytes;
    return RunDecoder(python3_, {bad_path});
  };
  const size_t stride = good.size() / 25 + 1;
  for (size_t cut = 0; cut < good.size(); cut += stride) {
    const process::CommandResult result = run_on(good.substr(0, cut));
    EXPECT_EQ(result.exit_code, 2) << "cut at " << cut << ": " << result.err;
    EXPECT_NE(result.err.find(bad_path), std::string::npos) << result.err;
    EXPECT_EQ(result.err.find("Traceback"), std::string::npos) << result.err;
  }
  for (size_t at = 0; at < good.size(); at += stride) {
    std::string bytes = good;
    bytes[at] = static_cast<char>(0xff);
    const process::CommandResult result = run_on(bytes);
    EXPECT_TRUE(result.exit_code == 0 || result.exit_code == 2)
        << "0xff at " << at << ": exit " << result.exit_code << ": " << result.err;
    EXPECT_EQ(result.err.find("Traceback"), std::string::npos) << result.err;
  }
  const process::CommandResult trailing = run_on(good + std::string(1, '\0'));
  EXPECT_EQ(trailing.exit_code, 2) << trailing.err;
  EXPECT_NE(trailing.err.find("left over"), std::string::npos) << trailing.err;

  const process::CommandResult missing = RunDecoder(python3_, {dir_.Path("absent.vmap")});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("absent.vmap"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace fleetmap::transport
