#include "server/fleet_map_store.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "common/transport/tile_payload.hpp"

namespace fleetmap::server {

StatusOr<std::unique_ptr<FleetMapStore>> FleetMapStore::Open(const Options& options) {
  store::StoreOptions store_options;
  store_options.max_history_rows = options.history_rows;
  store_options.lock_timeout_ms = options.lock_timeout.count();
  FLEETMAP_ASSIGN_OR_RETURN(
      std::unique_ptr<store::MapStore> store,
      store::MapStore::Open(options.path, store_options, [](const std::string& notice) {
        spdlog::warn("server: map store {}", notice);
      }));
  const store::StoreOpenReport& report = store->open_report();
  spdlog::info("server: map store {}: {}", options.path, report.Summary());
  for (const std::string& warning : report.warnings) {
    spdlog::warn("server: map store: {}", warning);
  }
  return std::unique_ptr<FleetMapStore>(new FleetMapStore(options, std::move(store)));
}

void FleetMapStore::Failed(const char* what, const Status& status) {
  spdlog::warn("server: map store: not storing {}: {}", what, status.message());
  ++errors_;
}

Status FleetMapStore::Restore(fusion::FleetMap& map) {
  // An operator's admission outlives a restart: admitted before their evidence comes back, the
  // robots are never weighed into quarantine again.
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<store::AdmissionRecord> admissions,
                            store_->Admissions());
  std::vector<std::string> admitted;
  for (const store::AdmissionRecord& admission : admissions) {
    map.AdmitRobot(admission.robot);
    admitted.push_back(admission.robot.value);
  }
  if (!admitted.empty()) {
    spdlog::info("server: {} robot(s) admitted by an operator before: {}", admitted.size(),
                 fmt::join(admitted, ", "));
  }
  FLEETMAP_ASSIGN_OR_RETURN(const StoreSync::Restored restored,
                            sync_.Restore(&map.fusion_to_restore()));
  for (const std::string& skipped : restored.skipped) {
    spdlog::warn("server: skipping a stored tile: {}", skipped);
  }
  spdlog::info("server: map store check: {} tile payloads decoded, {}", restored.tile_rows_checked,
               restored.corrupt_rows == 0
                   ? std::string("none corrupt")
                   : fmt::format("{} corrupt (skipped, named above)", restored.corrupt_rows));
  map.Restored();
  RestoreMapFrameTiles(map, restored.map_frame_tiles);
  const size_t restored_tiles = restored.from_evidence + restored.from_history;
  if (restored_tiles > 0) {
    spdlog::info(
        "server: restored {} robot tiles from {} ({} from their evidence, {} by fusing "
        "their stored revisions again)",
        restored_tiles, options_.path, restored.from_evidence, restored.from_history);
  }
  return Status::Ok();
}

void FleetMapStore::RestoreMapFrameTiles(fusion::FleetMap& map,
                                         const std::vector<store::TileRecord>& rows) {
  size_t restored = 0;
  for (const store::TileRecord& row : rows) {
    const RobotId& robot = row.owner.robot();
    const std::string name = options_.path + ": map-frame tile " + row.owner.key() + " (" +
                             std::to_string(row.tile.x) + ", " + std::to_string(row.tile.y) + ")";
    StatusOr<transport::VectorTileMessage> tile = transport::DecodeTilePayload(row.payload, name);
    if (!tile.ok()) {
      spdlog::warn("server: skipping a stored tile: {}", tile.status().message());
      continue;
    }
    if (tile->tile != row.tile || tile->robot_id != robot) {
      spdlog::warn("server: skipping a stored tile: {}: its payload is another robot's or tile's",
                   name);
      continue;
    }
    map.RestoreMapFrameTile(*std::move(tile));
    ++restored;
  }
  if (restored > 0) {
    spdlog::info("server: restored {} map-frame tiles of robots the server places", restored);
  }
}

void FleetMapStore::KeepTile(const store::TileOwner& owner, const vector_map::VectorTile& tile) {
  StatusOr<std::string> payload = transport::EncodeTilePayload(tile);
  if (!payload.ok()) return;  // it was decoded from the wire or made here; it encodes
  const Status queued = sync_.AddTile(store::TileRecord{
      owner, tile.tile, tile.revision,
      std::chrono::duration_cast<std::chrono::nanoseconds>(tile.stamp.time_since_epoch()).count(),
      std::move(payload).value()});
  if (!queued.ok()) Failed("a tile", queued);
}

void FleetMapStore::Keep(const fusion::FleetMapChanges& changes,
                         const std::vector<transport::VectorTileMessage>& fused) {
  for (const fusion::ReceivedTile& received : changes.received) {
    // A robot's map-frame tiles are kept apart from its fleet-frame rows: the fused map is not
    // rebuilt from them.
    const RobotId& robot = received.tile.robot_id;
    KeepTile(received.in_map_frame ? store::TileOwner::RobotMapFrame(robot)
                                   : store::TileOwner::Robot(robot),
             received.tile);
  }
  for (const fusion::ContributionChange& change : changes.contributions) {
    if (const Status queued = sync_.ContributionChanged(change.robot, change.tile); !queued.ok()) {
      Failed("a contribution", queued);
    }
  }
  for (const transport::VectorTileMessage& tile : fused) KeepTile(store::TileOwner::Fleet(), tile);
}

void FleetMapStore::KeepAdmission(const transport::RobotAdmissionMessage& admission) {
  const int64_t now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  const Status stored = store_->PutAdmission({admission.robot, admission.operator_name, now_ns});
  if (!stored.ok()) {
    // It holds until this server stops; the operator is told it will not outlive a restart.
    spdlog::error(
        "server: map store: the admission of {} is not stored (it holds until the server "
        "stops): {}",
        admission.robot.value, stored.message());
    ++errors_;
  }
}

void FleetMapStore::KeepRobot(store::RobotRecord robot) {
  if (const Status queued = sync_.AddRobot(std::move(robot)); !queued.ok()) {
    Failed("a robot", queued);
  }
}

void FleetMapStore::Flush(const fusion::FleetMap& map, std::chrono::steady_clock::time_point now) {
  const uint64_t failed_before = sync_.failed_attempts();
  const StoreSync::FlushResult result = sync_.Flush(map.fusion(), now);
  if (result == StoreSync::FlushResult::kFailed) {
    ++errors_;
    if (failed_before == 0) {
      spdlog::error(
          "server: map store is behind the fused map: {} ({} records wait; retrying every "
          "second, nothing is dropped)",
          sync_.last_error().message(), sync_.pending());
    }
  } else if (result == StoreSync::FlushResult::kWritten && failed_before > 0) {
    spdlog::info("server: map store caught up after {} failed writes", failed_before);
  }
}

void FleetMapStore::FinalFlush(const fusion::FleetMap& map) {
  Flush(map, std::chrono::steady_clock::time_point::max());
  if (sync_.pending() > 0) {
    spdlog::error("server: map store: stopping with {} records not stored: {}", sync_.pending(),
                  sync_.last_error().message());
  }
}

}  // namespace fleetmap::server
