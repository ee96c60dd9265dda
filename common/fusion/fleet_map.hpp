#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/notice.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/robot_frame.hpp"
#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"
#include "common/fusion/fair_tile_queue.hpp"
#include "common/fusion/fusion_options.hpp"
#include "common/fusion/map_frame_robots.hpp"
#include "common/fusion/tile_admission.hpp"
#include "common/fusion/tile_fusion.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/registration/placer.hpp"
#include "common/vector_map/vector_tile.hpp"

namespace fleetmap::fusion {

struct FleetMapOptions {
  FusionOptions fusion;
  // What a robot's tiles must satisfy, and its quotas.
  AdmissionOptions admission;
  // How robots whose tiles come in their own map frame are placed.
  registration::PlacementOptions placement;
  // A shard's server (docs/shards.md): only the region's fleet tiles are fused (robot tiles
  // elsewhere are refused, kOutsideRegion, and what map-frame robots carry elsewhere is left
  // out); robots at unknown poses are placed by their home shard only, the others follow it
  // (Follow), and the fleet frame is never anchored on a robot.
  std::optional<ShardAssignment> shard;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// Where an offered robot tile comes from: who pays for it, its size on the wire, and the frame
// its geometry is in.
struct TileOrigin {
  TileBudget::Source source;  // the robot id, and the participant and host that sent it
  size_t wire_bytes = 0;
  // The robot's own map frame (the fleet map places it), else the fleet frame.
  bool in_map_frame = false;
};

// A robot tile the fleet map applied, as it came (what a store keeps of a robot).
struct ReceivedTile {
  vector_map::VectorTile tile;
  bool in_map_frame = false;
  size_t wire_bytes = 0;  // as offered; 0 for the tiles of a grid
};

// What a robot contributes to one fleet tile, changed: its geometry in the fleet frame and the
// evidence stamp, or nothing when the contribution went.
struct ContributionChange {
  RobotId robot;
  TileId tile;
  std::optional<vector_map::VectorMap> map;
  Timestamp stamp{};
};

// A robot's tiles the fleet map dropped or could not fuse, and why.
struct DroppedTiles {
  RobotId robot;
  Refusal reason;
  std::string detail;
};

// Everything that changed since the last FleetMap::TakeChanged(): what a server publishes,
// stores and logs.
struct FleetMapChanges {
  std::vector<FusedTile> fused;  // fused tiles with a new revision
  std::vector<ReceivedTile> received;
  std::vector<ContributionChange> contributions;
  std::vector<TrustReport> standings;  // robots that entered or left quarantine (or still are)
  std::vector<RobotFrame> frames;      // frames table rows that changed
  std::vector<DroppedTiles> dropped;
  std::vector<RobotId> evicted;  // robots whose tiles all gave way to the memory budget
  std::vector<Notice> notices;
};

// The fleet's map, without DDS, a store or threads: robot tiles are offered (admission: the
// robot's quotas and the memory budget), wait in a queue fair between their senders, and are fused
// turn by turn into fleet tiles; robots whose tiles come in their own map frame are placed by
// registration (the frames table: given, anchored, placed or unplaced, the one holder of every
// robot's frame) and their tiles carried into the fleet frame; a robot whose map contradicts the
// fleet's is quarantined. What changed is taken out in one piece (TakeChanged) to publish, store
// and log. The server's fusion worker drives one; the unit tests drive it directly. Not
// thread-safe.
class FleetMap {
 public:
  static StatusOr<FleetMap> Create(const FleetMapOptions& options);

  // --- Tiles.
  // Admits a robot tile into the queue, or says why not. An admitted tile waits for its sender's
  // turn (FuseTurn); a newer revision of the same tile replaces it while it waits. `now` dates
  // stamps (system clock), `steady_now` rates.
  std::optional<TileAdmission::Refused> Offer(vector_map::VectorTile tile, const TileOrigin& origin,
                                              Timestamp now,
                                              std::chrono::steady_clock::time_point steady_now);
  // The robot removed one of its tiles: it leaves the queue, the fusion and the robot's quota.
  void Remove(const RobotId& robot, const TileId& tile);
  bool HasQueued() const { return !queue_.empty(); }
  // Fuses the next sender's turn (at most kMaxTilesPerTurn tiles, fewer when its tiles are
  // costly) and vectorizes the fleet tiles they changed; returns the tiles fused.
  size_t FuseTurn();
  // A robot's whole grid (the grid wire) at `fleet_from_map`, or in its own map frame (nullopt:
  // placed like tiles). `source` is its sender, for the quarantine.
  Status ApplyGrid(const RobotId& robot, const grid::OccupancyGrid& grid, Timestamp stamp,
                   std::optional<Pose2> fleet_from_map, const std::string& source);

  // --- Frames.
  // A robot joined: its map frame is given (fleet_from_map) or must be placed (nullopt).
  void Join(const RobotId& robot, std::optional<Pose2> fleet_from_map);
  // A shard: the frame another shard's server wrote for a robot (rt/fleetmap/robot_frames).
  // A robot homed on another shard takes its placement from there; the others' rows are this
  // fleet map's own business and ignored.
  void Follow(const RobotFrame& frame);
  // The registration to run next, if one is due (the robots in turn); the first robot with a map
  // anchors the fleet frame instead. Run it beside (RunPlacementJob), hand the result to Placed.
  std::optional<registration::PlacementJob> NextRegistration(
      std::chrono::steady_clock::time_point now);
  void Placed(const registration::PlacementResult& result,
              std::chrono::steady_clock::time_point now);
  const std::map<RobotId, RobotFrame>& frames() const { return placer_.frames(); }
  std::optional<RobotFrame> FrameOf(const RobotId& robot) const { return placer_.FrameOf(robot); }
  // Where the robot's map frame is in the fleet frame; nullopt while unplaced (or unknown).
  std::optional<Pose2> PlacementOf(const RobotId& robot) const;

  // --- Trust.
  // An operator admits the robot: its tiles are fused from now on. False: admitted before.
  bool AdmitRobot(const RobotId& robot) { return fusion_.AdmitRobot(robot); }
  TrustReport TrustOf(const RobotId& robot) const { return fusion_.TrustOf(robot); }

  // --- What changed, and what is.
  // Vectorizes what changed and hands over everything since the last call.
  FleetMapChanges TakeChanged();
  // The fused map as one grid (at most max_grid_cells: `shown` says which tiles).
  grid::OccupancyGrid FusedGrid(GridWindow* shown = nullptr) const {
    return fusion_.FusedGrid(shown);
  }
  const TileFusion& fusion() const { return fusion_; }
  const TileAdmission& admission() const { return admission_; }
  const FleetMapOptions& options() const { return options_; }

  // --- Restoring a stored map (before the first Offer).
  // The fusion to rebuild from a store; once done, Restored() counts what it holds against the
  // robots' quotas.
  TileFusion& fusion_to_restore() { return fusion_; }
  void Restored();
  // A stored tile of a robot whose tiles are in its own map frame: kept, unplaced until the
  // robot is placed again (placements are found again, not stored).
  void RestoreMapFrameTile(vector_map::VectorTile tile);

  // What one sender's turn may take before the next sender's (FairTileQueue sizes turns by
  // cost).
  static constexpr size_t kMaxTilesPerTurn = 16;
  static constexpr std::chrono::milliseconds kTurnTarget{20};

 private:
  // An admitted robot tile waiting for its sender's turn.
  struct PendingTile {
    vector_map::VectorTile tile;
    Timestamp evidence_stamp;
    bool in_map_frame = false;
    size_t wire_bytes = 0;
  };

  FleetMap(const FleetMapOptions& options, TileFusion fusion);

  void Apply(PendingTile pending);
  // Every tile of `robot`, queued or fused, to make room for an older robot's (global budget).
  void Evict(const RobotId& robot);
  // The robot's tile leaves fusion (and its map-frame tiles).
  void DropTileData(const RobotId& robot, const TileId& tile);
  // A robot's tile in its own map frame: kept, and its fleet tiles fused again once placed.
  void ApplyMapFrameTile(const RobotId& robot, const TileId& tile, vector_map::VectorMap map,
                         Timestamp stamp);
  // Fuses `robot`'s contributions to the fleet tiles `changed` anew from its map-frame tiles.
  void FuseMapFrameTilesAgain(const RobotId& robot, const std::set<TileId>& changed);
  void UpdateContribution(const RobotId& robot, const TileId& tile,
                          const vector_map::VectorMap& map, Timestamp stamp);
  void RemoveContribution(const RobotId& robot, const TileId& tile);
  // Carries the robot's map frame to `fleet_from_map` (a placement or a given frame).
  void MoveMapFrame(const RobotId& robot, const Pose2& fleet_from_map);
  // Vectorizes the fleet tiles that changed; the trust changes that came with them go to the
  // frames table.
  void FuseChanged();
  void Say(Notice::Level level, std::string text);
  bool InRegion(const TileId& tile) const { return !region_ || region_->Contains(tile); }
  // Whether this fleet map places `robot` when its frame is not known (always, unsharded).
  bool PlacesHere(const RobotId& robot) const {
    return !options_.shard || options_.shard->IsHomeOf(robot);
  }

  // The registration due for `robot`, if any: its own map on the fleet map, its group's merged
  // map on the fleet map (the group's root only), or its map on another unplaced robot's.
  std::optional<registration::PlacementJob> RegistrationFor(
      const RobotId& robot, std::chrono::steady_clock::time_point now) const;
  registration::PlacementJob JobFor(const RobotId& robot) const;
  // The maps of a group's members merged in its root's map frame.
  vector_map::VectorMap GroupMap(const registration::PlacementGroup& group) const;

  FleetMapOptions options_;
  std::optional<TileBox> region_;  // a shard's tiles
  TileFusion fusion_;
  MapFrameRobots map_frames_;
  registration::Placer placer_;
  TileAdmission admission_;
  // Served fairly by sender (the robot ids of one participant share one place), keyed by robot
  // and tile.
  FairTileQueue<PendingTile, std::string, std::pair<RobotId, TileId>> queue_;
  uint64_t fused_revisions_ = 0;  // fused tile revisions made: the fleet map changed
  RobotId last_registered_;       // whose map was registered last (round robin)
  FleetMapChanges changes_;
};

}  // namespace fleetmap::fusion
