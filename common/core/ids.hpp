#pragma once

// Strong ids: a tile index is not a cell index, and a robot id is not any string.

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

namespace fleetmap {

// A square tile of the fleet frame: it covers [x, x + 1) * tile_size by [y, y + 1) * tile_size.
struct TileId {
  int32_t x = 0;
  int32_t y = 0;

  friend auto operator<=>(const TileId&, const TileId&) = default;
};

std::ostream& operator<<(std::ostream& os, const TileId& id);

// A robot's name, as it appears in its ROS 2 namespace (`rt/<robot>/map`).
struct RobotId {
  std::string value;

  friend auto operator<=>(const RobotId&, const RobotId&) = default;
};

std::ostream& operator<<(std::ostream& os, const RobotId& id);

// A robot id must be usable as one ROS 2 name token: [A-Za-z][A-Za-z0-9_]*, at most 64 chars.
bool IsValidRobotName(const std::string& name);

// The fused map's owner name: fused tiles carry it as their robot id, and no robot may take it.
inline constexpr char kFleetRobotName[] = "fleet";

}  // namespace fleetmap

template <>
struct std::hash<fleetmap::TileId> {
  size_t operator()(const fleetmap::TileId& id) const noexcept {
    const uint64_t packed =
        (static_cast<uint64_t>(static_cast<uint32_t>(id.x)) << 32) | static_cast<uint32_t>(id.y);
    return std::hash<uint64_t>{}(packed);
  }
};

template <>
struct std::hash<fleetmap::RobotId> {
  size_t operator()(const fleetmap::RobotId& id) const noexcept {
    return std::hash<std::string>{}(id.value);
  }
};
