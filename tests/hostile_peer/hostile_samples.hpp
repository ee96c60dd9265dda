#pragma once

// What the hostile peer sends: owning twins of the two wire types (VectorTile, RobotStatus) and
// the tiles it builds. Written from idl/ and docs/file-formats.md alone, as a client of another
// vendor would: nothing here comes from fleetmap's libraries, so a fleetmap bug cannot hide in
// the attacker too.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace fleetmap::hostile {

// docs/file-formats.md, "VectorTile, field by field".
inline constexpr int kQuantaPerSide = 16000;  // tile_size / quantum
inline constexpr uint8_t kLayoutVersion = 4;
inline constexpr char kRobotTilesTopic[] = "rt/fleetmap/robot_tiles";
inline constexpr char kFusedTilesTopic[] = "rt/fleetmap/fused_tiles";
inline constexpr char kRobotStatusTopic[] = "rt/fleetmap/robot_status";

// builtin_interfaces/Time: seconds may be negative (a stamp before the epoch).
struct WireTime {
  int32_t sec = 0;
  uint32_t nanosec = 0;
};

// The system clock now, moved by `offset`.
WireTime StampFromNow(std::chrono::seconds offset = std::chrono::seconds(0));

struct TileKey {
  int32_t x = 0;
  int32_t y = 0;
  friend bool operator==(const TileKey&, const TileKey&) = default;
  friend auto operator<=>(const TileKey&, const TileKey&) = default;
};

// fleetmap_msgs/VectorTile, field for field.
struct TileSample {
  std::string robot_id;
  TileKey key;
  WireTime stamp;
  std::string frame_id = "fleet";
  uint32_t revision = 1;
  uint8_t layout_version = kLayoutVersion;
  double tile_size = 10.0;
  double quantum = 10.0 / kQuantaPerSide;
  float epsilon = 0.07f;
  float resolution = 0.05f;
  std::vector<uint8_t> obstacle_sizes;
  std::vector<uint8_t> obstacle_half_widths;
  std::vector<int16_t> obstacle_x;
  std::vector<int16_t> obstacle_y;
  std::vector<int16_t> point_x;
  std::vector<int16_t> point_y;
  std::vector<uint8_t> point_half_widths;
  std::vector<uint16_t> free_polygon_rings;
  std::vector<uint16_t> free_ring_sizes;
  std::vector<int16_t> free_x;
  std::vector<int16_t> free_y;
};

// fleetmap_msgs/RobotStatus, field for field (poses as x, y, theta).
struct StatusSample {
  std::string robot_id;
  WireTime stamp;
  double map_from_robot[3] = {0.0, 0.0, 0.0};
  double fleet_from_map[3] = {0.0, 0.0, 0.0};
  std::string map_topic = kRobotTilesTopic;  // "on the tile wire"
  uint32_t map_width = 200;
  uint32_t map_height = 200;
  float map_resolution = 0.05f;
  uint32_t map_revision = 1;
  uint64_t maps_published = 0;
  uint64_t tiles_published = 0;
  uint64_t bytes_published = 0;
  uint32_t sequence_number = 0;
};

// A valid tile: a free room with a closed wall around it and one point obstacle, as an honest
// agent would send.
TileSample WallTile(const std::string& robot, TileKey key, double tile_size);

// A valid tile that is explored and free everywhere, with no obstacle: written over a robot's tile
// it erases that robot's walls.
TileSample AllFreeTile(const std::string& robot, TileKey key, double tile_size);

// A valid but expensive tile: about `vertices` obstacle vertices in polylines of 255, each segment
// crossing much of the tile (so rasterizing it paints many cells), the whole tile free beneath.
// The same seed gives the same tile.
TileSample HeavyTile(const std::string& robot, TileKey key, double tile_size, int vertices,
                     uint32_t seed);

}  // namespace fleetmap::hostile
