#include "server/store_sync.hpp"

#include <algorithm>
#include <optional>
#include <tuple>
#include <utility>

#include "common/fusion/evidence_codec.hpp"
#include "common/transport/tile_payload.hpp"

namespace fleetmap::server {
namespace {

std::string Describe(const std::string& owner, const TileId& tile) {
  return owner + "'s tile (" + std::to_string(tile.x) + ", " + std::to_string(tile.y) + ")";
}

std::string Describe(const store::TileOwner& owner, const TileId& tile) {
  return Describe(owner.key(), tile);
}

Timestamp FromNanoseconds(int64_t ns) {
  return Timestamp(std::chrono::duration_cast<Clock::duration>(std::chrono::nanoseconds(ns)));
}

int64_t ToNanoseconds(Timestamp stamp) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(stamp.time_since_epoch()).count();
}

// Why a stored tile payload cannot be used, or nullopt: it does not decode, or it describes
// another owner or tile than its row's key (map-frame rows hold their robot's tiles).
std::optional<std::string> PayloadProblem(const store::TileRecord& row, const std::string& name) {
  StatusOr<transport::VectorTileMessage> tile = transport::DecodeTilePayload(row.payload, name);
  if (!tile.ok()) return std::string(tile.status().message());
  // A fused tile's payload names the fleet; a robot's, in either frame, the robot.
  const std::string owner = row.owner.is_fleet() ? kFleetRobotName : row.owner.robot().value;
  if (tile->tile != row.tile || tile->robot_id.value != owner) {
    return name + ": its payload is " + Describe(tile->robot_id.value, tile->tile) +
           ", not the row's key";
  }
  return std::nullopt;
}

bool Newer(const store::TileRecord& a, const store::TileRecord& b) {
  return std::tie(a.revision, a.stamp_ns) > std::tie(b.revision, b.stamp_ns);
}

}  // namespace

StoreSync::StoreSync(store::MapStore* store, Options options) : store_(store), options_(options) {}

StatusOr<StoreSync::Restored> StoreSync::Restore(fusion::TileFusion* fusion) {
  Restored restored;
  if (store_ == nullptr) return restored;
  const int cells_per_tile = fusion->options().CellsPerTile();
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<store::TileRecord> latest, store_->LatestTiles());
  FLEETMAP_ASSIGN_OR_RETURN(const auto corrupt, CheckTilePayloads(latest, &restored));
  std::set<std::pair<RobotId, TileId>> done;  // contributions restored from their evidence
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<store::EvidenceRecord> evidence, store_->Evidence());
  for (const store::EvidenceRecord& record : evidence) {
    const std::string name =
        store_->path() + ": evidence of " + Describe(record.robot.value, record.tile);
    if (record.robot.value == kFleetRobotName) {
      restored.skipped.push_back(name + ": the fleet owns no evidence");
      continue;
    }
    StatusOr<fusion::ContributionEvidence> decoded =
        fusion::DecodeEvidence(record.payload, cells_per_tile, name);
    if (!decoded.ok()) {
      restored.skipped.push_back(std::string(decoded.status().message()));
      continue;
    }
    const Status imported =
        fusion->ImportContribution(record.robot, record.tile, std::move(decoded).value());
    if (!imported.ok()) {
      restored.skipped.push_back(name + ": " + std::string(imported.message()));
      continue;
    }
    done.insert({record.robot, record.tile});
    ++restored.from_evidence;
  }

  // Robot tiles without evidence: a store from before schema version 3. Their revisions, fused
  // again in order, date each cell's evidence as the live fusion did (as far as the history goes).
  std::map<TileId, uint32_t> fused_revisions;
  for (const store::TileRecord& row : latest) {
    if (row.owner.is_fleet()) {
      // Fused tiles are rebuilt, not trusted; their revisions go on from the stored ones (the
      // revision is a column of its own: it holds even when the payload is corrupt).
      fused_revisions[row.tile] = row.revision;
      continue;
    }
    const bool row_corrupt = corrupt.count({row.owner, row.tile, row.revision, row.stamp_ns}) > 0;
    if (row.owner.kind() == store::TileOwner::Kind::kRobotMapFrame) {
      if (!row_corrupt) restored.map_frame_tiles.push_back(row);
      continue;
    }
    const RobotId& robot = row.owner.robot();
    if (done.count({robot, row.tile}) > 0) continue;
    FLEETMAP_ASSIGN_OR_RETURN(std::vector<store::TileRecord> revisions,
                              store_->TileHistory(row.owner, row.tile));
    if (revisions.empty() && !row_corrupt) revisions.push_back(row);  // kept without history
    size_t fused = 0;
    for (const store::TileRecord& record : revisions) {
      if (corrupt.count({record.owner, record.tile, record.revision, record.stamp_ns}) > 0) {
        continue;  // named by CheckTilePayloads
      }
      const std::string name = store_->path() + ": " + Describe(record.owner, record.tile) +
                               " revision " + std::to_string(record.revision);
      StatusOr<transport::VectorTileMessage> tile =
          transport::DecodeTilePayload(record.payload, name);
      if (!tile.ok()) {
        restored.skipped.push_back(std::string(tile.status().message()));
        continue;
      }
      // The payload's coordinates are relative to its own tile: fused under another key they
      // would land far away (and once kept start-up busy for good).
      if (tile->tile != record.tile || tile->robot_id != robot) {
        restored.skipped.push_back(name + ": its payload is " +
                                   Describe(tile->robot_id.value, tile->tile) +
                                   ", not the row's key");
        continue;
      }
      const Status updated =
          fusion->UpdateRobotTile(robot, record.tile, tile->map, FromNanoseconds(record.stamp_ns));
      if (!updated.ok()) {
        restored.skipped.push_back(name + ": " + std::string(updated.message()));
        continue;
      }
      ++fused;
    }
    if (fused == 0) continue;
    ++restored.from_history;
    changed_.insert({robot, row.tile});  // the store gets its evidence at the next Flush
  }
  fusion->ContinueRevisionsFrom(fused_revisions);
  return restored;
}

StatusOr<std::set<StoreSync::RowKey>> StoreSync::CheckTilePayloads(
    const std::vector<store::TileRecord>& latest, Restored* restored) const {
  std::set<RowKey> corrupt;
  const auto check = [&](const store::TileRecord& row, const std::string& table, size_t* named) {
    ++restored->tile_rows_checked;
    const std::string name = store_->path() + ": " + table + " row of " +
                             Describe(row.owner, row.tile) + " revision " +
                             std::to_string(row.revision);
    const std::optional<std::string> problem = PayloadProblem(row, name);
    if (!problem) return;
    corrupt.insert({row.owner, row.tile, row.revision, row.stamp_ns});
    ++restored->corrupt_rows;
    if (++*named <= kMaxNamedCorrupt) restored->skipped.push_back(*problem);
  };
  size_t named = 0;
  for (const store::TileRecord& row : latest) check(row, "tile_latest", &named);
  if (named > kMaxNamedCorrupt) {
    restored->skipped.push_back(store_->path() + ": and " +
                                std::to_string(named - kMaxNamedCorrupt) +
                                " more corrupt tile_latest rows");
  }
  named = 0;
  FLEETMAP_RETURN_IF_ERROR(store_->ForEachHistoryRow(
      [&](const store::TileRecord& row) { check(row, "tile_history", &named); }));
  if (named > kMaxNamedCorrupt) {
    restored->skipped.push_back(store_->path() + ": and " +
                                std::to_string(named - kMaxNamedCorrupt) +
                                " more corrupt tile_history rows");
  }
  return corrupt;
}

Status StoreSync::AddTile(store::TileRecord record) {
  if (store_ == nullptr) return Status::Ok();
  // One bad record must not make every later batch fail: refuse it here, alone.
  FLEETMAP_RETURN_IF_ERROR(store::ValidateTileRecord(record));
  if (!behind_) {
    tiles_.push_back(std::move(record));
    return Status::Ok();
  }
  const store::TileKey key{record.owner, record.tile};
  const auto [it, inserted] = tile_index_.try_emplace(key, tiles_.size());
  if (inserted) {
    tiles_.push_back(std::move(record));
  } else if (Newer(record, tiles_[it->second])) {
    tiles_[it->second] = std::move(record);
  }
  return Status::Ok();
}

Status StoreSync::ContributionChanged(const RobotId& robot, const TileId& tile) {
  if (store_ == nullptr) return Status::Ok();
  FLEETMAP_RETURN_IF_ERROR(store::ValidateEvidenceRecord({robot, tile, 0, ""}));
  changed_.insert({robot, tile});
  return Status::Ok();
}

Status StoreSync::AddRobot(store::RobotRecord robot) {
  if (store_ == nullptr) return Status::Ok();
  FLEETMAP_RETURN_IF_ERROR(store::ValidateRobotRecord(robot));
  const auto [it, inserted] = robots_.try_emplace(robot.robot, robot);
  if (inserted) return Status::Ok();
  // What PutRobot would make of both, in one record.
  store::RobotRecord& queued = it->second;
  robot.first_seen_ns = std::min(robot.first_seen_ns, queued.first_seen_ns);
  robot.last_seen_ns = std::max(robot.last_seen_ns, queued.last_seen_ns);
  queued = std::move(robot);
  return Status::Ok();
}

void StoreSync::Coalesce() {
  std::vector<store::TileRecord> tiles;
  tile_index_.clear();
  for (store::TileRecord& record : tiles_) {
    const auto [it, inserted] = tile_index_.try_emplace({record.owner, record.tile}, tiles.size());
    if (inserted) {
      tiles.push_back(std::move(record));
    } else if (Newer(record, tiles[it->second])) {
      tiles[it->second] = std::move(record);
    }
  }
  tiles_ = std::move(tiles);
}

StatusOr<store::StoreBatch> StoreSync::MakeBatch(const fusion::TileFusion& fusion) const {
  store::StoreBatch batch;
  std::set<store::TileKey> removed;
  for (const auto& [robot, tile] : changed_) {
    const std::optional<fusion::ContributionEvidence> evidence =
        fusion.ExportContribution(robot, tile);
    if (!evidence.has_value()) {
      const store::TileKey key{store::TileOwner::Robot(robot), tile};
      batch.removed.push_back(key);
      removed.insert(key);
      continue;
    }
    FLEETMAP_ASSIGN_OR_RETURN(std::string payload, fusion::EncodeEvidence(*evidence));
    batch.evidence.push_back(
        {robot, tile, std::max<int64_t>(0, ToNanoseconds(evidence->stamp)), std::move(payload)});
  }
  for (const store::TileRecord& record : tiles_) {
    // A revision of a tile that is gone since must not bring its rows back.
    if (removed.count({record.owner, record.tile}) == 0) batch.tiles.push_back(record);
  }
  for (const auto& [robot, record] : robots_) batch.robots.push_back(record);
  return batch;
}

StoreSync::FlushResult StoreSync::Flush(const fusion::TileFusion& fusion,
                                        std::chrono::steady_clock::time_point now) {
  if (store_ == nullptr || pending() == 0) return FlushResult::kIdle;
  if (behind_ && now < next_attempt_) return FlushResult::kWaiting;
  StatusOr<store::StoreBatch> batch = MakeBatch(fusion);
  Status written = batch.ok() ? store_->Write(*batch) : batch.status();
  if (written.ok()) {
    tiles_.clear();
    tile_index_.clear();
    changed_.clear();
    robots_.clear();
    behind_ = false;
    failed_attempts_ = 0;
    last_error_ = Status::Ok();
    return FlushResult::kWritten;
  }
  if (!behind_) Coalesce();
  behind_ = true;
  ++failed_attempts_;
  last_error_ = std::move(written);
  next_attempt_ = now + options_.retry_period;
  return FlushResult::kFailed;
}

}  // namespace fleetmap::server
