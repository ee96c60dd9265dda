#include "tests/hostile_peer/hostile_samples.hpp"

#include <algorithm>
#include <random>

namespace fleetmap::hostile {
namespace {

// A vertex may lie a little outside its tile; the peer stays inside so every tile is valid.
constexpr int16_t kSide = kQuantaPerSide;
constexpr int kMaxPolyline = 255;  // obstacle_sizes are uint8

TileSample Blank(const std::string& robot, TileKey key, double tile_size) {
  TileSample tile;
  tile.robot_id = robot;
  tile.key = key;
  tile.stamp = StampFromNow();
  tile.tile_size = tile_size;
  tile.quantum = tile_size / kQuantaPerSide;
  return tile;
}

// One free polygon: the ring (x0, y0) - (x1, y1), no holes.
void AddFreeRectangle(TileSample* tile, int16_t x0, int16_t y0, int16_t x1, int16_t y1) {
  tile->free_polygon_rings.push_back(1);
  tile->free_ring_sizes.push_back(4);
  tile->free_x.insert(tile->free_x.end(), {x0, x1, x1, x0});
  tile->free_y.insert(tile->free_y.end(), {y0, y0, y1, y1});
}

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
  constexpr int16_t kLow = kSide / 8;
  constexpr int16_t kHigh = kSide - kSide / 8;
  AddFreeRectangle(&tile, kLow, kLow, kHigh, kHigh);
  // A closed polyline repeats its first vertex (n >= 4).
  tile.obstacle_sizes = {5};
  tile.obstacle_x = {kLow, kHigh, kHigh, kLow, kLow};
  tile.obstacle_y = {kLow, kLow, kHigh, kHigh, kLow};
  tile.point_x = {kSide / 2};
  tile.point_y = {kSide / 2};
  return tile;
}

TileSample AllFreeTile(const std::string& robot, TileKey key, double tile_size) {
  TileSample tile = Blank(robot, key, tile_size);
  AddFreeRectangle(&tile, 0, 0, kSide, kSide);
  return tile;
}

TileSample HeavyTile(const std::string& robot, TileKey key, double tile_size, int vertices,
                     uint32_t seed) {
  TileSample tile = AllFreeTile(robot, key, tile_size);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> coordinate(0, kSide);
  for (int left = std::max(vertices, 2); left >= 2;) {
    const int n = std::min(left, kMaxPolyline);
    tile.obstacle_sizes.push_back(static_cast<uint8_t>(n));
    for (int i = 0; i < n; ++i) {
      tile.obstacle_x.push_back(static_cast<int16_t>(coordinate(random)));
      tile.obstacle_y.push_back(static_cast<int16_t>(coordinate(random)));
    }
    left -= n;
  }
  // The last vertex of a polyline is random, so it never repeats the first: every one is open.
  return tile;
}

}  // namespace fleetmap::hostile
