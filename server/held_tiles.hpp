#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "server/refusal_log.hpp"

namespace fleetmap::server {

// Tiles of robot ids that no status claims yet. An agent's status and its first tiles travel on
// different topics, so tiles may come first: the newest revision of each is held for a while and
// admitted once the id is claimed. Ids are free to invent, so what is held is bounded four ways:
// robot ids, tiles per id, tiles per participant (all its ids together) and decoded memory (the
// held geometry is charged as fusion::TileCost charges it). A tile over a bound is refused at once.
// Not thread-safe: the fusion worker owns it.
class HeldTiles {
 public:
  struct Limits {
    size_t max_robots = 64;
    size_t max_tiles_per_robot = 500;
    size_t max_tiles_per_participant = 500;
    uint64_t max_bytes = uint64_t{64} << 20;
    std::chrono::milliseconds wait{std::chrono::seconds(10)};
  };
  struct Refused {
    fusion::Refusal reason;
    std::string detail;
  };

  explicit HeldTiles(const Limits& limits) : limits_(limits) {}

  // Holds `event` (a tile of `participant` for an unclaimed id), replacing an older revision of
  // the same tile, or says which bound it would exceed.
  std::optional<Refused> Hold(transport::TileEvent event, const std::string& participant,
                              std::chrono::steady_clock::time_point now);

  // Takes out every held tile whose id is now `claimed`, to be admitted by the caller, and drops
  // those that waited longer than the limit (`expired` is told the robot and the tile).
  std::vector<transport::TileEvent> Release(
      std::chrono::steady_clock::time_point now, const std::function<bool(const RobotId&)>& claimed,
      const std::function<void(const RobotId&, const TileId&)>& expired);

  size_t tiles() const { return tiles_; }
  uint64_t bytes() const { return bytes_; }
  const Limits& limits() const { return limits_; }

 private:
  struct Held {
    transport::TileEvent event;
    std::string participant;
    uint64_t bytes = 0;
    std::chrono::steady_clock::time_point arrived;
  };
  void Forget(const Held& held);

  Limits limits_;
  std::map<RobotId, std::map<TileId, Held>> robots_;
  std::map<std::string, size_t> tiles_by_participant_;
  size_t tiles_ = 0;
  uint64_t bytes_ = 0;
};

// The memory a held tile keeps: its decoded geometry, as fusion::TileCost counts it.
uint64_t HeldBytes(const transport::TileEvent& event);

}  // namespace fleetmap::server
