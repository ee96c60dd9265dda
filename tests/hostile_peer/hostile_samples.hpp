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
inline constexpr int kStepsPerSide = 400;  // tile_size / quantum: half-cell steps of 5 cm cells
inline constexpr uint8_t kLayoutVersion = 5;
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
  uint8_t layout_version = kLayoutVersion;
  uint8_t compression = 0;  // plain geometry
  uint32_t revision = 1;
  uint32_t tile_size_mm = 10000;
  float epsilon = 0.07f;
  float resolution = 0.05f;
  // The lattice (quantum 0.025 m, origin (0, 0)), then no polyline, no point, no polygon.
  std::vector<uint8_t> geometry = {0x9a, 0x99, 0x99, 0x99, 0x99, 0x99, 0x99, 0x3f, 0, 0, 0, 0};
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

// A zstd bomb: `vertices` obstacle vertices stepping back and forth between two lattice points,
// zstd-compressed (compression 1): a few KB on the wire that decode to megabytes of vertices.
TileSample ZstdBombTile(const std::string& robot, TileKey key, double tile_size, int vertices);

}  // namespace fleetmap::hostile
