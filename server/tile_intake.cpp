#include "server/tile_intake.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "common/transport/topics.hpp"

namespace fleetmap::server {

StatusOr<std::unique_ptr<TileIntake>> TileIntake::Create(
    transport::Participant& participant, const fusion::AdmissionOptions& admission,
    std::chrono::milliseconds unclaimed_wait, std::shared_ptr<RobotRegistry> registry,
    std::shared_ptr<WakeUp> wake_up, RefusalSink refused, std::optional<ShardTileScope> shard) {
  HeldTiles::Limits held;
  held.max_tiles_per_robot = admission.max_tiles_per_robot;
  // One robot's worth for all the ids of a participant together: an agent's status reaches the
  // server within its first tiles, so waiting is for the odd late status, not for floods.
  held.max_tiles_per_participant = admission.max_tiles_per_robot;
  held.max_bytes = admission.budget.max_memory_bytes / 8;
  held.wait = unclaimed_wait;
  std::unique_ptr<TileIntake> self(new TileIntake(std::move(registry), held, std::move(refused)));
  self->unclaimed_wait_ = unclaimed_wait;
  std::optional<transport::TileRegionSelection> region;
  if (shard) region = shard->Selection();
  self->shard_ = std::move(shard);
  self->participant_ = &participant;
  self->wake_up_ = wake_up;
  self->limits_ = admission.DecodeLimits();
  FLEETMAP_ASSIGN_OR_RETURN(
      self->reader_,
      transport::VectorTileReader::Create(participant, transport::kRobotTilesTopic,
                                          std::move(wake_up), admission.DecodeLimits(), region));
  return self;
}

// The reader goes before the participant that owns its topic (the caller's).
TileIntake::~TileIntake() = default;

void TileIntake::Drain(fusion::FleetMap& map) {
  const Timestamp now = Clock::now();
  const auto steady = std::chrono::steady_clock::now();
  for (transport::TileEvent& event : reader_->Drain(kEventsPerDrain)) {
    // A shard takes a map-frame robot's tiles from that robot's own reader only.
    if (shard_ && whole_robots_.count(event.tile.robot_id) > 0) continue;
    Offer(std::move(event), map, now, steady);
  }
  if (shard_) {
    if (const Status followed = FollowMapFrameRobots(); !followed.ok() && !said_full_) {
      spdlog::warn("server: {}", followed.message());  // once: the next robots find it full too
      said_full_ = true;
    }
    for (auto& [robot, reader] : whole_robots_) {
      for (transport::TileEvent& event : reader->Drain(kEventsPerDrain)) {
        Offer(std::move(event), map, now, steady);
      }
    }
  }
  ReleaseHeld(map, steady);
}

void TileIntake::Offer(transport::TileEvent event, fusion::FleetMap& map, Timestamp now,
                       std::chrono::steady_clock::time_point steady) {
  const RobotId robot = event.tile.robot_id;
  const std::string participant =
      event.writer.empty() ? std::string() : RobotRegistry::ParticipantOf(event.writer);
  const auto refuse = [&](fusion::Refusal reason, const std::string& detail) {
    refused_(robot, reason, detail, participant);
  };
  if (event.kind == transport::TileEvent::Kind::kRejected) {
    // Past the decode limits (a zstd bomb, a million vertices): refused before it was inflated.
    const bool too_large = event.error.code() == StatusCode::kResourceExhausted;
    refuse(too_large ? fusion::Refusal::kDecodedSize : fusion::Refusal::kMalformed,
           event.error.message());
    return;
  }
  if (auto refused = fusion::TileAdmission::CheckRobotId(event.tile)) {
    refuse(refused->reason, refused->detail);
    return;
  }
  // A tile its writer may not send for this robot id, refused naming both and why.
  const auto refuse_sender = [&](fusion::Refusal reason, const char* which) {
    refuse(reason,
           fmt::format("tile ({}, {}) for robot {} from participant {}, which {}",
                       event.tile.tile.x, event.tile.tile.y, robot.value, participant, which));
  };
  switch (registry_->WhoSpeaks(robot, event.writer)) {
    case RobotRegistry::Speaker::kOther:
      refuse_sender(fusion::Refusal::kNotOwner, "does not own it");
      return;
    case RobotRegistry::Speaker::kNotItself:
      refuse_sender(fusion::Refusal::kNotItself, "authenticated as another identity");
      return;
    case RobotRegistry::Speaker::kOverCap:
      refuse_sender(fusion::Refusal::kTooManyIds,
                    "already speaks for as many robots as a participant may");
      return;
    case RobotRegistry::Speaker::kUnclaimed:
      // Its status (and with it, who owns the id) may still be on its way: held, bounded.
      if (auto refused = held_.Hold(std::move(event), participant, steady)) {
        refuse(refused->reason, refused->detail);
      }
      return;
    case RobotRegistry::Speaker::kOwner:
      break;
  }
  if (event.kind == transport::TileEvent::Kind::kRemoved) {
    map.Remove(robot, event.tile.tile);
    return;
  }
  const fusion::TileOrigin origin{
      {robot, participant, event.host}, event.serialized_bytes, registry_->TilesInMapFrame(robot)};
  if (shard_ && !origin.in_map_frame && !shard_->Owns(event.tile.tile)) {
    const ShardTileScope::Outside outside = shard_->NoteOutside(robot, event.tile.tile, steady);
    if (outside.report_now) {
      const ShardRegion& own = shard_->shard().region();
      refuse(fusion::Refusal::kOutsideRegion,
             fmt::format("tile ({}, {}) of robot {} lies on no shard's region, so no server fuses "
                         "it (this shard, {}: [{}, {}] x [{}, {}] m; reported once a minute per "
                         "robot; docs/shards.md)",
                         event.tile.tile.x, event.tile.tile.y, robot.value, own.name, own.min_x,
                         own.max_x, own.min_y, own.max_y));
    }
    return;
  }
  if (auto refused = map.Offer(std::move(event.tile), origin, now, steady)) {
    refuse(refused->reason, refused->detail);
  }
}

Status TileIntake::FollowMapFrameRobots() {
  for (const RobotId& robot : registry_->MapFrameRobots()) {
    if (whole_robots_.count(robot) > 0) continue;
    if (whole_robots_.size() >= kMaxWholeRobots) {
      return ResourceExhaustedError(fmt::format(
          "this shard reads {} robots at unknown poses already; robot {}'s tiles outside its "
          "region are not read",
          kMaxWholeRobots, robot.value));
    }
    FLEETMAP_ASSIGN_OR_RETURN(whole_robots_[robot], transport::VectorTileReader::CreateForRobot(
                                                        *participant_, transport::kRobotTilesTopic,
                                                        robot, wake_up_, limits_));
  }
  return Status::Ok();
}

void TileIntake::ReleaseHeld(fusion::FleetMap& map, std::chrono::steady_clock::time_point steady) {
  const auto claimed = [&](const RobotId& robot) { return !registry_->OwnerOf(robot).empty(); };
  const auto expired = [&](const RobotId& robot, const TileId& tile) {
    refused_(robot, fusion::Refusal::kUnclaimed,
             fmt::format("tile ({}, {}) waited {} s for a status claiming robot {}; dropped",
                         tile.x, tile.y,
                         std::chrono::duration_cast<std::chrono::seconds>(unclaimed_wait_).count(),
                         robot.value),
             std::string());
  };
  const Timestamp now = Clock::now();
  // Offer() sorts the owner's tiles from the others now that the id is claimed.
  for (transport::TileEvent& event : held_.Release(steady, claimed, expired)) {
    Offer(std::move(event), map, now, steady);
  }
}

}  // namespace fleetmap::server
