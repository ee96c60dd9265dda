#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/fusion/fleet_map.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "server/held_tiles.hpp"
#include "server/robot_registry.hpp"
#include "server/shard_tile_scope.hpp"

namespace fleetmap::server {

// Takes robot tiles off rt/fleetmap/robot_tiles and offers them to the fleet map: a sample that
// did not decode, or that its writer may not send for its robot id (another participant owns the
// id, or its identity is another's), is refused; a tile of an id no status claims yet is held
// until one does (bounded); the others go through the fleet map's admission. Every refusal goes
// to `refused`, naming the participant that sent it. Not thread-safe: the fusion worker's.
class TileIntake {
 public:
  using RefusalSink = std::function<void(const RobotId& robot, fusion::Refusal reason,
                                         const std::string& detail, const std::string& sender)>;

  // `registry` says who owns each id and in which frame its tiles come; `wake_up` is woken when
  // a sample arrives. A shard's server reads what `shard` selects (docs/shards.md).
  static StatusOr<std::unique_ptr<TileIntake>> Create(
      transport::Participant& participant, const fusion::AdmissionOptions& admission,
      std::chrono::milliseconds unclaimed_wait, std::shared_ptr<RobotRegistry> registry,
      std::shared_ptr<WakeUp> wake_up, RefusalSink refused, std::optional<ShardTileScope> shard);
  ~TileIntake();

  // Offers a bounded share of what arrived (participants in turn) to `map`, and the held tiles
  // whose ids are claimed now: a flood's backlog is decoded and admitted a share at a time, while
  // the loop fuses between calls.
  void Drain(fusion::FleetMap& map);

  size_t queued() const { return reader_->queued(); }
  size_t dropped() const { return reader_->dropped(); }
  uint64_t tiles_on_no_shard() const { return shard_ ? shard_->orphan_tiles() : 0; }
  uint64_t tiles_of_other_shards() const { return shard_ ? shard_->other_shards_tiles() : 0; }

  static constexpr size_t kEventsPerDrain = 512;
  // Robots at unknown poses a shard reads whole, a reader each (ids are free to claim).
  static constexpr size_t kMaxWholeRobots = 256;

 private:
  TileIntake(std::shared_ptr<RobotRegistry> registry, const HeldTiles::Limits& held,
             RefusalSink refused)
      : registry_(std::move(registry)), held_(held), refused_(std::move(refused)) {}

  void Offer(transport::TileEvent event, fusion::FleetMap& map, Timestamp now,
             std::chrono::steady_clock::time_point steady);
  void ReleaseHeld(fusion::FleetMap& map, std::chrono::steady_clock::time_point steady);
  // A shard reads the tiles of each robot that sends in its own map frame through a reader of
  // its own (their tile keys say nothing of the fleet frame): made as the robot joins, it gets
  // the robot's whole history from its writer.
  Status FollowMapFrameRobots();

  std::shared_ptr<RobotRegistry> registry_;
  HeldTiles held_;  // tiles whose robot's status has not come yet
  RefusalSink refused_;
  std::chrono::milliseconds unclaimed_wait_{};
  std::unique_ptr<transport::VectorTileReader> reader_;
  std::optional<ShardTileScope> shard_;
  std::map<RobotId, std::unique_ptr<transport::VectorTileReader>> whole_robots_;  // a shard's
  transport::Participant* participant_ = nullptr;  // the caller's; for the readers of whole robots
  std::shared_ptr<WakeUp> wake_up_;
  transport::TileDecodeLimits limits_;
  bool said_full_ = false;
};

}  // namespace fleetmap::server
