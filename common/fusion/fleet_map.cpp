#include "common/fusion/fleet_map.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::fusion {
namespace {

bool HasOccupiedCell(const grid::OccupancyGrid& grid) {
  return std::find(grid.data().begin(), grid.data().end(), grid::kOccupiedValue) !=
         grid.data().end();
}

RobotFrame::Standing FrameStanding(Standing standing) {
  switch (standing) {
    case Standing::kQuarantined:
      return RobotFrame::Standing::kQuarantined;
    case Standing::kAdmitted:
      return RobotFrame::Standing::kAdmitted;
    case Standing::kTrusted:
      break;
  }
  return RobotFrame::Standing::kTrusted;
}

}  // namespace

Status FleetMapOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(fusion.Validate());
  FLEETMAP_RETURN_IF_ERROR(placement.Validate());
  return admission.Validate();
}

void FleetMapOptions::Describe(OptionsPrinter& out) const {
  out.Nested("fusion", fusion);
  out.Nested("admission", admission);
  out.Nested("placement", placement);
  if (shard) out.Add("shard", shard->name);
}

StatusOr<FleetMap> FleetMap::Create(const FleetMapOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  FLEETMAP_ASSIGN_OR_RETURN(TileFusion fusion, TileFusion::Create(options.fusion));
  return FleetMap(options, std::move(fusion));
}

FleetMap::FleetMap(const FleetMapOptions& options, TileFusion fusion)
    : options_(options),
      region_(options.shard
                  ? std::optional<TileBox>(options.shard->region().Tiles(options.fusion.tile_size))
                  : std::nullopt),
      fusion_(std::move(fusion)),
      map_frames_(options.fusion.tile_size),
      placer_(options.placement),
      admission_(options.admission, options.fusion) {}

void FleetMap::Say(Notice::Level level, std::string text) {
  changes_.notices.push_back(Notice{level, std::move(text)});
}

std::optional<TileAdmission::Refused> FleetMap::Offer(
    vector_map::VectorTile tile, const TileOrigin& origin, Timestamp now,
    std::chrono::steady_clock::time_point steady_now) {
  if (!origin.in_map_frame && !InRegion(tile.tile)) {
    return TileAdmission::Refused{
        Refusal::kOutsideRegion,
        fmt::format("tile ({}, {}) of robot {} lies outside this shard's tiles ({}, {})..({}, {})",
                    tile.tile.x, tile.tile.y, tile.robot_id.value, region_->min_x, region_->min_y,
                    region_->max_x, region_->max_y)};
  }
  TileAdmission::Verdict verdict =
      admission_.Admit(tile, origin.wire_bytes, origin.source, now, steady_now);
  if (auto* refused = std::get_if<TileAdmission::Refused>(&verdict)) return std::move(*refused);
  auto& admitted = std::get<TileAdmission::Admitted>(verdict);
  for (const RobotId& newer : admitted.evict) Evict(newer);
  const RobotId robot = tile.robot_id;
  const TileId key = tile.tile;
  // Ids of one participant share its place in the queue; a tile without a sender pays as its id.
  const std::string payer =
      origin.source.participant.empty() ? "robot " + robot.value : origin.source.participant;
  if (!origin.source.participant.empty()) fusion_.SetRobotSource(robot, origin.source.participant);
  queue_.Push(payer, {robot, key},
              PendingTile{std::move(tile), admitted.evidence_stamp, origin.in_map_frame,
                          origin.wire_bytes});
  return std::nullopt;
}

void FleetMap::Remove(const RobotId& robot, const TileId& tile) {
  queue_.EraseIf([&](const auto& key) { return key.first == robot && key.second == tile; });
  admission_.Forget(robot, tile);
  DropTileData(robot, tile);
}

void FleetMap::Evict(const RobotId& robot) {
  const size_t queued = queue_.EraseIf([&](const auto& key) { return key.first == robot; });
  const std::vector<TileId> tiles = admission_.DropRobot(robot);
  for (const TileId& tile : tiles) DropTileData(robot, tile);
  changes_.dropped.push_back(DroppedTiles{
      robot, Refusal::kMemoryBudget,
      fmt::format("the server's memory budget for all robots' tiles is spent: robot {}, claimed "
                  "after the robots that need it, gives way ({} tiles and {} queued dropped)",
                  robot.value, tiles.size(), queued)});
  changes_.evicted.push_back(robot);
}

void FleetMap::DropTileData(const RobotId& robot, const TileId& tile) {
  if (map_frames_.Knows(robot)) {
    FuseMapFrameTilesAgain(robot, map_frames_.RemoveTile(robot, tile));
    return;
  }
  RemoveContribution(robot, tile);
}

size_t FleetMap::FuseTurn() {
  std::string payer;
  const auto start = std::chrono::steady_clock::now();
  std::vector<PendingTile> turn = queue_.NextTurn(kMaxTilesPerTurn, kTurnTarget, &payer);
  const size_t tiles = turn.size();
  for (PendingTile& pending : turn) Apply(std::move(pending));
  // The turn's cost includes vectorizing what it changed: that is what delays the others.
  FuseChanged();
  queue_.Charge(payer, std::chrono::steady_clock::now() - start, tiles);
  return tiles;
}

void FleetMap::Apply(PendingTile pending) {
  vector_map::VectorTile& tile = pending.tile;
  const RobotId robot = tile.robot_id;
  if (pending.in_map_frame) {
    ApplyMapFrameTile(robot, tile.tile, tile.map, pending.evidence_stamp);
  } else {
    const Status updated =
        fusion_.UpdateRobotTile(robot, tile.tile, tile.map, pending.evidence_stamp);
    if (!updated.ok()) {
      changes_.dropped.push_back(DroppedTiles{
          robot, Refusal::kMalformed,
          fmt::format("tile ({}, {}): {}", tile.tile.x, tile.tile.y, updated.message())});
      return;
    }
    changes_.contributions.push_back(
        ContributionChange{robot, tile.tile, tile.map, pending.evidence_stamp});
  }
  changes_.received.push_back(
      ReceivedTile{std::move(tile), pending.in_map_frame, pending.wire_bytes});
}

void FleetMap::ApplyMapFrameTile(const RobotId& robot, const TileId& tile,
                                 vector_map::VectorMap map, Timestamp stamp) {
  if (!map_frames_.Knows(robot)) placer_.Unplaced(robot);
  FuseMapFrameTilesAgain(robot, map_frames_.UpdateTile(robot, tile, std::move(map), stamp));
  // A robot given a frame before its first map-frame tile came: carried there at once.
  if (!map_frames_.placement(robot)) {
    if (const std::optional<Pose2> given = PlacementOf(robot);
        given && (placer_.IsGiven(robot) || placer_.IsFollowed(robot))) {
      MoveMapFrame(robot, *given);
    }
  }
}

void FleetMap::FuseMapFrameTilesAgain(const RobotId& robot, const std::set<TileId>& changed) {
  for (const TileId& tile : changed) {
    std::optional<MapFrameRobots::FleetTile> contribution = map_frames_.Contribution(robot, tile);
    if (!contribution) {
      RemoveContribution(robot, tile);
    } else {
      UpdateContribution(robot, tile, contribution->map, contribution->stamp);
    }
  }
}

void FleetMap::UpdateContribution(const RobotId& robot, const TileId& tile,
                                  const vector_map::VectorMap& map, Timestamp stamp) {
  if (!InRegion(tile)) return;  // another shard's part of the robot's map
  if (const Status updated = fusion_.UpdateRobotTile(robot, tile, map, stamp); !updated.ok()) {
    // Placed beyond the fleet map's range: that part of the robot's map is not fused.
    Say(Notice::Level::kWarning, fmt::format("robot {}: {}", robot.value, updated.message()));
    return;
  }
  changes_.contributions.push_back(ContributionChange{robot, tile, map, stamp});
}

void FleetMap::RemoveContribution(const RobotId& robot, const TileId& tile) {
  fusion_.RemoveRobotTile(robot, tile);
  changes_.contributions.push_back(ContributionChange{robot, tile, std::nullopt, Timestamp{}});
}

Status FleetMap::ApplyGrid(const RobotId& robot, const grid::OccupancyGrid& grid, Timestamp stamp,
                           std::optional<Pose2> fleet_from_map, const std::string& source) {
  vector_map::TiledVectorizeOptions options;
  options.tile_size = options_.fusion.tile_size;
  // A grid whose frame is not known is tiled in its own frame and placed like tiles; so is one
  // whose given frame is rotated (fleet tiles are cut on the fleet frame's axis-aligned cells),
  // then carried into the fleet frame at that transform.
  const bool rotated = fleet_from_map && fleet_from_map->yaw != 0.0;
  const bool in_map_frame = !fleet_from_map || rotated;
  const Pose2 tiling_frame = in_map_frame ? Pose2{} : *fleet_from_map;
  FLEETMAP_ASSIGN_OR_RETURN(const vector_map::TiledVectorMap tiled,
                            vector_map::VectorizeTiled(grid, tiling_frame.ToTransform(), options));
  if (!source.empty()) fusion_.SetRobotSource(robot, source);
  if (rotated) Join(robot, fleet_from_map);
  for (const auto& [tile, map] : tiled.tiles) {
    if (in_map_frame) {
      ApplyMapFrameTile(robot, tile, map, stamp);
      // Kept as received: a restart places the robot again from these.
      changes_.received.push_back(ReceivedTile{
          vector_map::VectorTile{robot, tile, 0, stamp, options_.fusion.tile_size, map}, true});
    } else {
      UpdateContribution(robot, tile, map, stamp);
    }
  }
  return Status::Ok();
}

void FleetMap::Join(const RobotId& robot, std::optional<Pose2> fleet_from_map) {
  if (!fleet_from_map) {
    placer_.Unplaced(robot);
    return;
  }
  placer_.Given(robot, *fleet_from_map);
  // Tiles in its own map frame (a rotated given frame) are carried into the fleet frame at it,
  // exactly as a placement by registration would; fleet-frame tiles need nothing.
  if (map_frames_.Knows(robot) && map_frames_.placement(robot) != fleet_from_map) {
    MoveMapFrame(robot, *fleet_from_map);
  }
}

void FleetMap::Follow(const RobotFrame& frame) {
  if (PlacesHere(frame.robot) || !frame.placed() || frame.state == RobotFrame::State::kGiven) {
    return;
  }
  placer_.Follow(frame);
  if (map_frames_.Knows(frame.robot) &&
      map_frames_.placement(frame.robot) != frame.fleet_from_map) {
    MoveMapFrame(frame.robot, frame.fleet_from_map);
  }
}

void FleetMap::MoveMapFrame(const RobotId& robot, const Pose2& fleet_from_map) {
  FuseMapFrameTilesAgain(robot, map_frames_.Place(robot, fleet_from_map));
}

std::optional<Pose2> FleetMap::PlacementOf(const RobotId& robot) const {
  return placer_.PlacementOf(robot);
}

void FleetMap::Placed(const registration::PlacementResult& result,
                      std::chrono::steady_clock::time_point now) {
  for (const registration::Placer::Decision& decision : placer_.Decide(result, now)) {
    MoveMapFrame(decision.robot, decision.fleet_from_map);
  }
}

std::optional<registration::PlacementJob> FleetMap::NextRegistration(
    std::chrono::steady_clock::time_point now) {
  if (placer_.Busy()) return std::nullopt;
  const std::vector<RobotId> robots = map_frames_.robots();
  // With no frame known yet, the first robot with a map anchors the fleet frame; never on a
  // shard's map: the shards' regions are drawn in a fleet frame that exists already.
  if (!options_.shard && !placer_.AnyPlaced() && fusion_.contribution_count() == 0) {
    for (const RobotId& robot : robots) {
      if (map_frames_.tile_count(robot) == 0) continue;
      MoveMapFrame(robot, placer_.Anchor(robot).fleet_from_map);
      return std::nullopt;
    }
    return std::nullopt;
  }
  // Round robin from the robot after the last one registered: however many robots keep changing
  // their maps (a hostile peer's among them), none waits behind the others.
  std::vector<RobotId> turn = robots;
  std::rotate(turn.begin(), std::upper_bound(turn.begin(), turn.end(), last_registered_),
              turn.end());
  for (const RobotId& robot : turn) {
    if (map_frames_.tile_count(robot) == 0 || !PlacesHere(robot)) continue;
    if (std::optional<registration::PlacementJob> job = RegistrationFor(robot, now)) {
      last_registered_ = robot;
      placer_.Submitted(*job, now);
      return job;
    }
  }
  return std::nullopt;
}

registration::PlacementJob FleetMap::JobFor(const RobotId& robot) const {
  registration::PlacementJob job;
  job.robot = robot;
  job.resolution = options_.fusion.FusedResolution();
  job.map_changes = map_frames_.changes(robot);
  return job;
}

vector_map::VectorMap FleetMap::GroupMap(const registration::PlacementGroup& group) const {
  vector_map::VectorMap map = map_frames_.MapOf(group.root);
  for (const auto& [member, root_from_member] : group.root_from_member) {
    if (member == group.root) continue;
    map.Append(vector_map::Transformed(map_frames_.MapOf(member), root_from_member.ToTransform(),
                                       map.frame_id));
  }
  return map;
}

std::optional<registration::PlacementJob> FleetMap::RegistrationFor(
    const RobotId& robot, std::chrono::steady_clock::time_point now) const {
  // 1. The robot's own map against the fleet map without it: to place it (unplaced) or to check
  //    its placement (placed).
  registration::PlacementJob alone = JobFor(robot);
  alone.current = map_frames_.placement(robot);
  alone.target_changes = fused_revisions_;
  grid::OccupancyGrid fleet_map;  // rasterized once, when a registration on it is due
  const auto fleet_target = [&]() -> const grid::OccupancyGrid& {
    if (fleet_map.empty()) fleet_map = fusion_.FusedGrid(nullptr, &robot);
    return fleet_map;
  };
  if (placer_.Due(alone.key(), alone.map_changes, alone.target_changes, now)) {
    if (!HasOccupiedCell(fleet_target())) return std::nullopt;  // nothing to register on yet
    alone.target = fleet_target();
    alone.map = map_frames_.MapOf(robot);
    return alone;
  }
  if (alone.current) return std::nullopt;
  // 2. An unplaced robot registered to other unplaced ones: their maps merged in the root's frame
  //    (what they mapped together may meet the fleet map where no member's alone does). Only the
  //    root registers the group; placing it places the others (Placer::PlaceFollowers).
  const registration::PlacementGroup group = placer_.GroupOf(robot);
  if (group.root == robot && group.root_from_member.size() > 1) {
    registration::PlacementJob merged = alone;
    for (const auto& [member, unused] : group.root_from_member) {
      if (member == robot) continue;
      merged.group.push_back(member);
      merged.map_changes += map_frames_.changes(member);
    }
    if (placer_.Due(merged.key(), merged.map_changes, merged.target_changes, now) &&
        HasOccupiedCell(fleet_target())) {
      merged.target = fleet_target();
      merged.map = GroupMap(group);
      return merged;
    }
  }
  // 3. Not on the fleet map (yet): perhaps on another unplaced robot's, outside its group.
  for (const RobotId& other : placer_.UnplacedOthers(robot)) {
    registration::PlacementJob pair = JobFor(robot);
    pair.target_robot = other;
    pair.target_changes = map_frames_.changes(other);
    if (map_frames_.tile_count(other) == 0 ||
        !placer_.Due(pair.key(), pair.map_changes, pair.target_changes, now)) {
      continue;
    }
    pair.map = map_frames_.MapOf(robot);
    pair.target_map = map_frames_.MapOf(other);
    return pair;
  }
  return std::nullopt;
}

void FleetMap::FuseChanged() {
  StatusOr<std::vector<FusedTile>> fused = fusion_.FuseChanged();
  admission_.SetSharedBytes(fusion_.SharedEvidenceBytes());
  for (TrustReport& report : fusion_.TakeTrustChanges()) {
    placer_.SetStanding(
        report.robot,
        registration::Placer::Standing{FrameStanding(report.standing), report.reason, report.share,
                                       report.contradicted_m, report.area_min, report.area_max});
    changes_.standings.push_back(std::move(report));
  }
  if (!fused.ok()) {
    Say(Notice::Level::kError, "fusion failed: " + fused.status().message());
    return;
  }
  fused_revisions_ += fused->size();
  for (FusedTile& tile : *fused) changes_.fused.push_back(std::move(tile));
}

FleetMapChanges FleetMap::TakeChanged() {
  FuseChanged();
  for (RobotFrame& frame : placer_.TakeChangedFrames()) {
    // A shard writes the rows of the robots it places (and given ones, which every shard
    // knows): a reader takes each row from one writer, and the home shard's is the one.
    if (!PlacesHere(frame.robot) && frame.state != RobotFrame::State::kGiven) continue;
    changes_.frames.push_back(std::move(frame));
  }
  for (Notice& notice : placer_.TakeNotices()) changes_.notices.push_back(std::move(notice));
  return std::exchange(changes_, {});
}

void FleetMap::Restored() {
  // Restored tiles count towards their robots' quotas, as if they had just been admitted.
  for (const auto& [robot, tile] : fusion_.contributions()) admission_.Adopt(robot, tile);
}

void FleetMap::RestoreMapFrameTile(vector_map::VectorTile tile) {
  // Unplaced until registration places the robot again (its placement is not stored: it is
  // found again from the map, against the restored fleet map).
  admission_.Adopt(tile.robot_id, tile.tile);
  placer_.Unplaced(tile.robot_id);
  map_frames_.UpdateTile(tile.robot_id, tile.tile, std::move(tile.map), tile.stamp);
}

}  // namespace fleetmap::fusion
