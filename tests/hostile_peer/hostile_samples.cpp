#include "tests/hostile_peer/hostile_samples.hpp"

#include <algorithm>
#include <cstring>
#include <random>

#include <zstd.h>

namespace fleetmap::hostile {
namespace {

// A vertex may lie a little outside its tile; the peer stays inside so every tile is valid.
constexpr int64_t kSide = kStepsPerSide;
constexpr int kMaxPolyline = 255;

TileSample Blank(const std::string& robot, TileKey key, double tile_size) {
  TileSample tile;
  tile.robot_id = robot;
  tile.key = key;
  tile.stamp = StampFromNow();
  tile.tile_size_mm = static_cast<uint32_t>(tile_size * 1000.0 + 0.5);
  return tile;
}

// The geometry bytes: the lattice (the quantum's eight bytes, little-endian, and 0: origin (0, 0)),
// then LEB128 varints, zigzag for signed ones, and vertices as steps from the one before, the first
// from step (0, 0) of the fleet frame. Vertices are given from the tile's corner.
class GeometryWriter {
 public:
  GeometryWriter(TileKey key, double tile_size)
      : corner_x_(key.x * kSide), corner_y_(key.y * kSide) {
    const double quantum = tile_size / kStepsPerSide;
    uint64_t bits;
    std::memcpy(&bits, &quantum, sizeof bits);
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<uint8_t>(bits >> (8 * i)));
    bytes_.push_back(0);
  }

  void Unsigned(uint64_t value) {
    for (; value >= 0x80; value >>= 7) bytes_.push_back(static_cast<uint8_t>(value | 0x80));
    bytes_.push_back(static_cast<uint8_t>(value));
  }
  void Byte(uint8_t value) { bytes_.push_back(value); }
  void Vertex(int64_t x, int64_t y) {
    Signed(corner_x_ + x - last_x_);
    Signed(corner_y_ + y - last_y_);
    last_x_ = corner_x_ + x;
    last_y_ = corner_y_ + y;
  }
  // One polygon of one ring, the rectangle (x0, y0) - (x1, y1).
  void FreeRectangle(int64_t x0, int64_t y0, int64_t x1, int64_t y1) {
    Unsigned(1);  // polygons
    Unsigned(1);  // rings
    Unsigned(4);  // vertices
    Vertex(x0, y0);
    Vertex(x1, y0);
    Vertex(x1, y1);
    Vertex(x0, y1);
  }
  std::vector<uint8_t> Take() { return std::move(bytes_); }

 private:
  void Signed(int64_t value) {
    Unsigned((static_cast<uint64_t>(value) << 1) ^ static_cast<uint64_t>(value >> 63));
  }

  std::vector<uint8_t> bytes_;
  int64_t corner_x_;
  int64_t corner_y_;
  int64_t last_x_ = 0;
  int64_t last_y_ = 0;
};

}  // namespace

WireTime StampFromNow(std::chrono::seconds offset) {
  const auto since_epoch = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::system_clock::now().time_since_epoch() + offset);
  const auto seconds = std::chrono::floor<std::chrono::seconds>(since_epoch);
  return WireTime{static_cast<int32_t>(seconds.count()),
                  static_cast<uint32_t>((since_epoch - seconds).count())};
}

TileSample WallTile(const std::string& robot, TileKey key, double tile_size) {
  TileSample tile = Blank(robot, key, tile_size);
  constexpr int64_t kLow = kSide / 8;
  constexpr int64_t kHigh = kSide - kSide / 8;
  GeometryWriter out(key, tile_size);
  out.Unsigned(1);                 // one polyline:
  out.Unsigned((4 - 2) << 1 | 1);  // 4 vertices, closed
  out.Byte(0);                     // half width 0
  out.Vertex(kLow, kLow);
  out.Vertex(kHigh, kLow);
  out.Vertex(kHigh, kHigh);
  out.Vertex(kLow, kHigh);
  out.Unsigned(1);  // one point obstacle
  out.Byte(0);
  out.Vertex(kSide / 2, kSide / 2);
  out.FreeRectangle(kLow, kLow, kHigh, kHigh);
  tile.geometry = out.Take();
  return tile;
}

TileSample AllFreeTile(const std::string& robot, TileKey key, double tile_size) {
  TileSample tile = Blank(robot, key, tile_size);
  GeometryWriter out(key, tile_size);
  out.Unsigned(0);  // no polyline
  out.Unsigned(0);  // no point
  out.FreeRectangle(0, 0, kSide, kSide);
  tile.geometry = out.Take();
  return tile;
}

TileSample HeavyTile(const std::string& robot, TileKey key, double tile_size, int vertices,
                     uint32_t seed) {
  TileSample tile = Blank(robot, key, tile_size);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int64_t> coordinate(0, kSide);
  std::vector<int> sizes;
  for (int left = std::max(vertices, 2); left >= 2; left -= sizes.back()) {
    sizes.push_back(std::min(left, kMaxPolyline));
  }
  GeometryWriter out(key, tile_size);
  out.Unsigned(sizes.size());
  for (const int n : sizes) {
    out.Unsigned(static_cast<uint64_t>(n - 2) << 1);  // open
    out.Byte(0);
    for (int i = 0; i < n; ++i) out.Vertex(coordinate(random), coordinate(random));
  }
  out.Unsigned(0);  // no point
  out.FreeRectangle(0, 0, kSide, kSide);
  tile.geometry = out.Take();
  return tile;
}

TileSample ZstdBombTile(const std::string& robot, TileKey key, double tile_size, int vertices) {
  TileSample tile = Blank(robot, key, tile_size);
  std::vector<int> sizes;
  for (int left = std::max(vertices, 2); left >= 2; left -= sizes.back()) {
    sizes.push_back(std::min(left, kMaxPolyline));
  }
  GeometryWriter out(key, tile_size);
  out.Unsigned(sizes.size());
  for (const int n : sizes) {
    out.Unsigned(static_cast<uint64_t>(n - 2) << 1);  // open
    out.Byte(0);
    for (int i = 0; i < n; ++i) out.Vertex(10 + i % 2, 10);
  }
  out.Unsigned(0);  // no point
  out.FreeRectangle(0, 0, kSide, kSide);
  const std::vector<uint8_t> plain = out.Take();
  // One frame that states its content size, as the layout requires.
  std::vector<uint8_t> frame(ZSTD_compressBound(plain.size()));
  const size_t size = ZSTD_compress(frame.data(), frame.size(), plain.data(), plain.size(), 19);
  frame.resize(ZSTD_isError(size) ? 0 : size);
  tile.compression = 1;
  tile.geometry = std::move(frame);
  return tile;
}

}  // namespace fleetmap::hostile
