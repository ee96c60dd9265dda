#include "server/fusion_worker.hpp"

#include <spdlog/spdlog.h>

#include "common/transport/tile_payload.hpp"
#include "common/transport/topics.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::server {
void FusionWorker::Remember(const std::string& owner, const transport::VectorTileMessage& tile) {
  StatusOr<std::string> payload = transport::EncodeTilePayload(tile);
  if (!payload.ok()) return;  // it was decoded from the wire; it encodes
  const Status queued = sync_->AddTile(store::TileRecord{
      owner, tile.tile, tile.revision,
      std::chrono::duration_cast<std::chrono::nanoseconds>(tile.stamp.time_since_epoch()).count(),
      std::move(payload).value()});
  if (!queued.ok()) {
    spdlog::warn("server: map store: not storing a tile: {}", queued.message());
    std::lock_guard lock(stats_mutex_);
    ++stats_.store_errors;
    return;
  }
  if (owner != store::kFleetOwner) RememberContribution(owner, tile.tile);
}

void FusionWorker::RememberContribution(const std::string& robot, const TileId& tile) {
  if (store_ == nullptr) return;
  if (const Status queued = sync_->ContributionChanged(robot, tile); !queued.ok()) {
    spdlog::warn("server: map store: not storing a contribution: {}", queued.message());
    std::lock_guard lock(stats_mutex_);
    ++stats_.store_errors;
  }
}

StatusOr<std::unique_ptr<FusionWorker>> FusionWorker::Create(
    transport::Participant& participant, const FusionWorkerOptions& options,
    std::shared_ptr<RobotRegistry> registry) {
  FLEETMAP_ASSIGN_OR_RETURN(fusion::TileFusion fusion, fusion::TileFusion::Create(options.fusion));
  std::unique_ptr<FusionWorker> worker(
      new FusionWorker(options, std::move(fusion), std::move(registry)));
  FLEETMAP_ASSIGN_OR_RETURN(worker->tile_reader_,
                            transport::VectorTileReader::Create(
                                participant, transport::kRobotTilesTopic, worker->wake_up_));
  FLEETMAP_ASSIGN_OR_RETURN(worker->fused_writer_, transport::VectorTileWriter::Create(
                                                       participant, transport::kFusedTilesTopic));
  FLEETMAP_ASSIGN_OR_RETURN(worker->map_writer_, transport::OccupancyGridWriter::Create(
                                                     participant, transport::kFleetMapTopic));
  if (!options.store_path.empty()) {
    store::StoreOptions store_options;
    store_options.max_history_rows = options.history_rows;
    FLEETMAP_ASSIGN_OR_RETURN(worker->store_,
                              store::MapStore::Open(options.store_path, store_options));
    const store::StoreOpenReport& report = worker->store_->open_report();
    spdlog::info("server: map store {}: {}", options.store_path, report.Summary());
    for (const std::string& warning : report.warnings) {
      spdlog::warn("server: map store: {}", warning);
    }
  }
  worker->sync_ = std::make_unique<StoreSync>(worker->store_.get(), StoreSync::Options{});
  if (worker->store_ != nullptr) FLEETMAP_RETURN_IF_ERROR(worker->Restore());
  worker->sessions_ =
      std::make_unique<SessionArchive>(options.fusion.tile_size, worker->store_.get());
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<std::string> skipped, worker->sessions_->Restore());
  for (const std::string& warning : skipped) {
    spdlog::warn("server: skipping a stored mapping session: {}", warning);
  }
  worker->stats_.sessions_finished = worker->sessions_->finished().size();
  return worker;
}

FusionWorker::~FusionWorker() {
  Stop();
  // Readers and writers go before the participant that owns their topics (the caller's).
  tile_reader_.reset();
  fused_writer_.reset();
  map_writer_.reset();
}

Status FusionWorker::Restore() {
  FLEETMAP_ASSIGN_OR_RETURN(const StoreSync::Restored restored, sync_->Restore(&fusion_));
  for (const std::string& skipped : restored.skipped) {
    spdlog::warn("server: skipping a stored tile: {}", skipped);
  }
  std::lock_guard lock(stats_mutex_);
  stats_.restored_tiles = restored.from_evidence + restored.from_history;
  if (stats_.restored_tiles > 0) {
    spdlog::info(
        "server: restored {} robot tiles from {} ({} from their evidence, {} by fusing "
        "their stored revisions again)",
        stats_.restored_tiles, options_.store_path, restored.from_evidence, restored.from_history);
  }
  return Status::Ok();
}

void FusionWorker::RecordRobot(store::RobotRecord robot) {
  robot_records_.Push(std::move(robot));
  wake_up_->Notify();
}

void FusionWorker::SetListeners(FusedMapListener on_fused_map, SessionsListener on_sessions) {
  on_fused_map_ = std::move(on_fused_map);
  on_sessions_ = std::move(on_sessions);
}

void FusionWorker::Start() {
  if (on_sessions_ && !sessions_->finished().empty()) on_sessions_(sessions_->finished());
  thread_ = std::thread([this] { Loop(); });
}

void FusionWorker::Stop() {
  stop_.store(true);
  wake_up_->Notify();
  if (thread_.joinable()) thread_.join();
}

void FusionWorker::SubmitGrid(const std::string& robot, transport::MapMessage map,
                              Pose2 fleet_from_map) {
  grids_.Push(GridUpdate{robot, std::move(map), fleet_from_map});
  wake_up_->Notify();
}

FusionStats FusionWorker::stats() const {
  std::lock_guard lock(stats_mutex_);
  return stats_;
}

void FusionWorker::Loop() {
  while (!stop_.load()) {
    wake_up_->WaitFor(std::chrono::milliseconds(50));
    HandleTileEvents();
    HandleGrids();
    PublishFused(std::chrono::steady_clock::now());
    HandleRobotRecords();
    Persist();
  }
  Persist(std::chrono::steady_clock::time_point::max());
  if (sync_->pending() > 0) {
    spdlog::error("server: map store: stopping with {} records not stored: {}", sync_->pending(),
                  sync_->last_error().message());
  }
}

void FusionWorker::HandleRobotRecords() {
  std::vector<store::RobotRecord> records = robot_records_.Drain();
  for (const store::RobotRecord& robot : records) {
    if (robot.state == "active") {
      sessions_->Rejoin(robot.robot);
      continue;
    }
    const Timestamp ended{
        std::chrono::duration_cast<Clock::duration>(std::chrono::nanoseconds(robot.last_seen_ns))};
    StatusOr<std::optional<MappingSession>> finished = sessions_->EndSession(robot.robot, ended);
    if (!finished.ok()) {
      spdlog::error("server: map store: {}", finished.status().message());
      std::lock_guard lock(stats_mutex_);
      ++stats_.store_errors;
    } else if (!finished->has_value()) {
      continue;
    } else {
      spdlog::info("server: mapping session {} of {} finished ({} tiles)", (**finished).id,
                   robot.robot, (**finished).map.tiles.size());
    }
    {
      std::lock_guard lock(stats_mutex_);
      stats_.sessions_finished = sessions_->finished().size();
    }
    if (on_sessions_) on_sessions_(sessions_->finished());
  }
  if (store_ == nullptr) return;
  for (store::RobotRecord& robot : records) {
    if (const Status queued = sync_->AddRobot(std::move(robot)); !queued.ok()) {
      spdlog::error("server: map store: not storing a robot: {}", queued.message());
      std::lock_guard lock(stats_mutex_);
      ++stats_.store_errors;
    }
  }
}

void FusionWorker::Persist() { Persist(std::chrono::steady_clock::now()); }

void FusionWorker::Persist(std::chrono::steady_clock::time_point now) {
  if (store_ == nullptr) return;
  // One transaction for everything this round: SQLite's cost is per commit, not per row.
  const uint64_t failed_before = sync_->failed_attempts();
  const StoreSync::FlushResult result = sync_->Flush(fusion_, now);
  if (result == StoreSync::FlushResult::kFailed && failed_before == 0) {
    spdlog::error(
        "server: map store is behind the fused map: {} ({} records wait; retrying "
        "every second, nothing is dropped)",
        sync_->last_error().message(), sync_->pending());
  } else if (result == StoreSync::FlushResult::kWritten && failed_before > 0) {
    spdlog::info("server: map store caught up after {} failed writes", failed_before);
  }
  std::lock_guard lock(stats_mutex_);
  if (result == StoreSync::FlushResult::kFailed) ++stats_.store_errors;
  stats_.store_behind = sync_->behind();
  stats_.store_pending = sync_->pending();
}

void FusionWorker::HandleTileEvents() {
  for (transport::TileEvent& event : tile_reader_->Drain()) {
    const std::string& robot = event.tile.robot_id;
    if (event.kind == transport::TileEvent::Kind::kRejected) {
      spdlog::warn("server: dropped a robot tile: {}", event.error.message());
      std::lock_guard lock(stats_mutex_);
      if (robot.empty()) {
        ++stats_.rejected_unattributed;
      } else {
        ++stats_.robots[robot].rejected;
      }
      continue;
    }
    if (!registry_->MaySpeakFor(robot, event.writer)) {
      spdlog::warn("server: dropped tile ({}, {}) claiming robot {} from a second agent",
                   event.tile.tile.x, event.tile.tile.y, robot);
      std::lock_guard lock(stats_mutex_);
      ++stats_.robots[robot].rejected;
      continue;
    }
    if (event.kind == transport::TileEvent::Kind::kRemoved) {
      fusion_.RemoveRobotTile(robot, event.tile.tile);
      RememberContribution(robot, event.tile.tile);
      sessions_->RemoveTile(robot, event.tile.tile);
      continue;
    }
    const Status updated =
        fusion_.UpdateRobotTile(robot, event.tile.tile, event.tile.map, event.tile.stamp);
    if (updated.ok()) {
      sessions_->RecordTile(robot, event.tile.tile, event.tile.map, event.tile.stamp);
      if (store_ != nullptr) Remember(robot, event.tile);
    }
    std::lock_guard lock(stats_mutex_);
    FusionStats::Robot& stats = stats_.robots[robot];
    if (!updated.ok()) {
      ++stats.rejected;
      spdlog::warn("server: dropped tile ({}, {}) of {}: {}", event.tile.tile.x, event.tile.tile.y,
                   robot, updated.message());
      continue;
    }
    ++stats.tiles;
    stats.bytes += event.serialized_bytes;
  }
}

void FusionWorker::HandleGrids() {
  for (GridUpdate& update : grids_.Drain()) {
    vector_map::TiledVectorizeOptions options;
    options.tile_size = options_.fusion.tile_size;
    const auto tiled =
        vector_map::VectorizeTiled(update.map.grid, update.fleet_from_map.ToTransform(), options);
    if (!tiled.ok()) {
      spdlog::warn("server: cannot fuse the grid of {}: {}", update.robot,
                   tiled.status().message());
      std::lock_guard lock(stats_mutex_);
      ++stats_.robots[update.robot].rejected;
      continue;
    }
    for (const auto& [tile, map] : tiled->tiles) {
      const Status updated = fusion_.UpdateRobotTile(update.robot, tile, map, update.map.stamp);
      if (!updated.ok()) {
        spdlog::warn("server: {}: {}", update.robot, updated.message());
        continue;
      }
      sessions_->RecordTile(update.robot, tile, map, update.map.stamp);
      RememberContribution(update.robot, tile);
    }
  }
}

void FusionWorker::PublishFused(std::chrono::steady_clock::time_point now) {
  StatusOr<std::vector<fusion::FusedTile>> changed = fusion_.FuseChanged();
  if (!changed.ok()) {
    spdlog::error("server: fusion failed: {}", changed.status().message());
    return;
  }
  uint64_t bytes = 0;
  for (fusion::FusedTile& tile : *changed) {
    transport::VectorTileMessage message;
    message.robot_id = store::kFleetOwner;
    message.tile = tile.tile;
    message.revision = tile.revision;
    message.stamp = tile.source_stamp;  // lets receivers measure end-to-end latency
    message.tile_size = options_.fusion.tile_size;
    message.map = std::move(tile.map);
    StatusOr<size_t> written = fused_writer_->Write(message);
    if (!written.ok()) {
      spdlog::warn("server: {}", written.status().message());
      continue;
    }
    bytes += *written;
    if (store_ != nullptr) Remember(store::kFleetOwner, message);
  }
  if (!changed->empty()) map_dirty_ = true;
  bool map_sent = false;
  if (map_dirty_ && now - last_map_ >= options_.map_period) {
    transport::MapMessage map;
    map.grid = fusion_.FusedGrid();
    map.frame_id = "fleet";
    map.stamp = Clock::now();
    if (StatusOr<size_t> written = map_writer_->Write(map); written.ok()) {
      if (on_fused_map_) on_fused_map_(map.grid);
      map_sent = true;
      map_dirty_ = false;
      last_map_ = now;
    } else {
      spdlog::warn("server: {}", written.status().message());
    }
  }
  std::lock_guard lock(stats_mutex_);
  stats_.fused_tiles_published += changed->size();
  stats_.fused_bytes_published += bytes;
  stats_.maps_published += map_sent ? 1 : 0;
  stats_.fused_tiles = fusion_.fused_tiles().size();
}

}  // namespace fleetmap::server
