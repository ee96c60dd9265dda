#include "server/fusion_worker.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <malloc.h>

#include <algorithm>

#include "common/transport/tile_payload.hpp"
#include "common/transport/topics.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::server {
namespace {

// Hands memory freed in large amounts (a robot's dropped tiles) back to the system: glibc keeps
// freed heap below its top and in its arenas otherwise, and the server's RSS would not go down.
void ReturnFreedMemory() { malloc_trim(0); }

bool HasOccupiedCell(const grid::OccupancyGrid& grid) {
  return std::find(grid.data().begin(), grid.data().end(), grid::kOccupiedValue) !=
         grid.data().end();
}

}  // namespace

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
  // A robot's own tile is its contribution; its map-frame tiles and fused tiles are not.
  if (IsValidRobotName(owner) && owner != store::kFleetOwner) {
    RememberContribution(RobotId{owner}, tile.tile);
  }
}

void FusionWorker::RememberContribution(const RobotId& robot, const TileId& tile) {
  if (store_ == nullptr) return;
  if (const Status queued = sync_->ContributionChanged(robot, tile); !queued.ok()) {
    spdlog::warn("server: map store: not storing a contribution: {}", queued.message());
    std::lock_guard lock(stats_mutex_);
    ++stats_.store_errors;
  }
}

HeldTiles::Limits FusionWorker::HeldLimits(const FusionWorkerOptions& options) {
  HeldTiles::Limits limits;
  limits.max_tiles_per_robot = options.admission.max_tiles_per_robot;
  // One robot's worth for all the ids of a participant together: an agent's status reaches
  // the server within its first tiles, so waiting is for the odd late status, not for floods.
  limits.max_tiles_per_participant = options.admission.max_tiles_per_robot;
  limits.max_bytes = options.admission.budget.max_memory_bytes / 8;
  limits.wait = options.unclaimed_wait;
  return limits;
}

StatusOr<std::unique_ptr<FusionWorker>> FusionWorker::Create(
    transport::Participant& participant, const FusionWorkerOptions& options,
    std::shared_ptr<RobotRegistry> registry) {
  FLEETMAP_ASSIGN_OR_RETURN(fusion::TileFusion fusion, fusion::TileFusion::Create(options.fusion));
  std::unique_ptr<FusionWorker> worker(
      new FusionWorker(options, std::move(fusion), std::move(registry)));
  // The store first: a server refused its store (another holds it) never joins the topics.
  if (!options.store_path.empty()) {
    store::StoreOptions store_options;
    store_options.max_history_rows = options.history_rows;
    store_options.lock_timeout_ms = options.store_lock_timeout.count();
    FLEETMAP_ASSIGN_OR_RETURN(
        worker->store_,
        store::MapStore::Open(options.store_path, store_options, [](const std::string& notice) {
          spdlog::warn("server: map store {}", notice);
        }));
    const store::StoreOpenReport& report = worker->store_->open_report();
    spdlog::info("server: map store {}: {}", options.store_path, report.Summary());
    for (const std::string& warning : report.warnings) {
      spdlog::warn("server: map store: {}", warning);
    }
  }
  FLEETMAP_ASSIGN_OR_RETURN(worker->tile_reader_,
                            transport::VectorTileReader::Create(
                                participant, transport::kRobotTilesTopic, worker->thread_.wake_up(),
                                options.admission.DecodeLimits()));
  FLEETMAP_ASSIGN_OR_RETURN(worker->fused_writer_, transport::VectorTileWriter::Create(
                                                       participant, transport::kFusedTilesTopic));
  FLEETMAP_ASSIGN_OR_RETURN(worker->map_writer_, transport::OccupancyGridWriter::Create(
                                                     participant, transport::kFleetMapTopic));
  FLEETMAP_ASSIGN_OR_RETURN(worker->admission_reader_, transport::RobotAdmissionReader::Create(
                                                           participant, worker->thread_.wake_up()));
  FLEETMAP_ASSIGN_OR_RETURN(worker->placer_, RobotPlacer::Create(participant, options.placement));
  worker->sync_ = std::make_unique<StoreSync>(worker->store_.get(), StoreSync::Options{});
  if (worker->store_ != nullptr) FLEETMAP_RETURN_IF_ERROR(worker->Restore());
  worker->sessions_ = std::make_unique<SessionArchive>(
      options.fusion.tile_size, worker->store_.get(), options.sessions_in_memory);
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<std::string> skipped, worker->sessions_->Restore());
  for (const std::string& warning : skipped) {
    spdlog::warn("server: skipping a stored mapping session: {}", warning);
  }
  worker->stats_.sessions_finished = worker->sessions_->finished_count();
  return worker;
}

FusionWorker::~FusionWorker() {
  Stop();
  // Readers and writers go before the participant that owns their topics (the caller's).
  tile_reader_.reset();
  fused_writer_.reset();
  map_writer_.reset();
  admission_reader_.reset();
  placer_.reset();
}

Status FusionWorker::Restore() {
  // An operator's admission outlives a restart: admitted before their evidence comes back, the
  // robots are never weighed into quarantine again.
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<store::AdmissionRecord> admissions,
                            store_->Admissions());
  std::vector<std::string> admitted;
  for (const store::AdmissionRecord& admission : admissions) {
    fusion_.AdmitRobot(admission.robot);
    admitted.push_back(admission.robot.value);
  }
  if (!admitted.empty()) {
    spdlog::info("server: {} robot(s) admitted by an operator before: {}", admitted.size(),
                 fmt::join(admitted, ", "));
  }
  FLEETMAP_ASSIGN_OR_RETURN(const StoreSync::Restored restored, sync_->Restore(&fusion_));
  for (const std::string& skipped : restored.skipped) {
    spdlog::warn("server: skipping a stored tile: {}", skipped);
  }
  spdlog::info("server: map store check: {} tile payloads decoded, {}", restored.tile_rows_checked,
               restored.corrupt_rows == 0
                   ? std::string("none corrupt")
                   : fmt::format("{} corrupt (skipped, named above)", restored.corrupt_rows));
  // Restored tiles count towards their robots' quotas, as if they had just been admitted.
  for (const auto& [robot, tile] : fusion_.contributions()) admission_.Adopt(robot, tile);
  RestoreMapFrameTiles(restored.map_frame_tiles);
  const size_t restored_tiles = restored.from_evidence + restored.from_history;
  if (restored_tiles > 0) {
    spdlog::info(
        "server: restored {} robot tiles from {} ({} from their evidence, {} by fusing "
        "their stored revisions again)",
        restored_tiles, options_.store_path, restored.from_evidence, restored.from_history);
  }
  return Status::Ok();
}

void FusionWorker::RecordRobot(store::RobotRecord robot) {
  robot_records_.Push(std::move(robot));
  thread_.Wake();
}

void FusionWorker::SetListeners(FusedMapListener on_fused_map, SessionsListener on_sessions) {
  on_fused_map_ = std::move(on_fused_map);
  on_sessions_ = std::move(on_sessions);
}

void FusionWorker::Start() {
  if (on_sessions_ && !sessions_->finished().empty()) on_sessions_(sessions_->finished());
  thread_.Start([this] { return Round(); }, [this] { AtStop(); });
}

void FusionWorker::Stop() { thread_.Stop(); }

void FusionWorker::SetServing(bool serving) {
  serving_ = serving;
  thread_.Wake();
}

void FusionWorker::SubmitGrid(const RobotId& robot, transport::MapMessage map,
                              std::optional<Pose2> fleet_from_map) {
  grids_.Push(GridUpdate{robot, std::move(map), fleet_from_map});
  thread_.Wake();
}

void FusionWorker::NoteRobotFrame(const RobotId& robot, std::optional<Pose2> fleet_from_map) {
  frame_notes_.Push(RobotFrameNote{robot, fleet_from_map});
  thread_.Wake();
}

FusionStats FusionWorker::stats() const {
  FusionStats stats;
  {
    std::lock_guard lock(stats_mutex_);
    stats = stats_;
  }
  stats.tile_events_dropped = tile_reader_->dropped();
  stats.grids_dropped = grids_.dropped();
  stats.robot_records_dropped = robot_records_.dropped();
  return stats;
}

bool FusionWorker::Round() {
  HandleAdmissions();
  HandleTileEvents();
  // Bounded, so that new samples are drained (and a flood coalesced) while a backlog lasts.
  FuseQueuedTiles(kFusionSlice);
  HandleGrids();
  HandlePlacements(std::chrono::steady_clock::now());
  PublishFused(std::chrono::steady_clock::now());
  HandleRobotRecords();
  Persist();
  // A backlog (fused or still to admit): the next round starts without waiting.
  return !queue_.empty() || tile_reader_->queued() > 0;
}

void FusionWorker::AtStop() {
  Persist(std::chrono::steady_clock::time_point::max());
  if (sync_->pending() > 0) {
    spdlog::error("server: map store: stopping with {} records not stored: {}", sync_->pending(),
                  sync_->last_error().message());
  }
}

void FusionWorker::HandleRobotRecords() {
  std::vector<store::RobotRecord> records = robot_records_.Drain();
  std::vector<std::string> discarded;
  for (const store::RobotRecord& robot : records) {
    if (robot.state == "active") {
      sessions_->Rejoin(robot.robot);
      continue;
    }
    if (const std::string why = WhySessionIsNotKept(robot.robot); !why.empty()) {
      cut_sessions_.erase(robot.robot);
      const size_t tiles = sessions_->DiscardSession(robot.robot);
      if (tiles > 0)
        discarded.push_back(fmt::format("{} ({} tiles: {})", robot.robot.value, tiles, why));
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
                   robot.robot.value, (**finished).map.tiles.size());
    }
    {
      std::lock_guard lock(stats_mutex_);
      stats_.sessions_finished = sessions_->finished_count();
    }
    if (on_sessions_) on_sessions_(sessions_->finished());
  }
  if (!discarded.empty()) {
    // One line a round however many ids end: a flood of ids must not flood the log.
    constexpr size_t kNamed = 3;
    const size_t named = std::min(discarded.size(), kNamed);
    spdlog::info(
        "server: {} mapping session(s) not kept for object learning: {}{}", discarded.size(),
        fmt::join(discarded.begin(), discarded.begin() + static_cast<std::ptrdiff_t>(named), "; "),
        discarded.size() > named ? fmt::format(" and {} more", discarded.size() - named)
                                 : std::string());
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
  const Timestamp now = Clock::now();
  const auto steady = std::chrono::steady_clock::now();
  // A bounded share per call, participants in turn: the loop fuses between calls, so a flood's
  // backlog is admitted (and decoded) a share at a time while honest tiles keep their turn.
  for (transport::TileEvent& event : tile_reader_->Drain(kTileEventsPerDrain)) {
    Admit(std::move(event), now, steady);
  }
  ReleaseHeldTiles(steady);
}

void FusionWorker::Refuse(const RobotId& robot, Refusal reason, const std::string& detail,
                          const std::string& participant) {
  // A name that is not a robot name (empty, too long) is not used as a key anywhere.
  const bool named = IsValidRobotName(robot.value);
  refusals_.RefuseFrom(participant, named ? robot.value : std::string(), reason, detail);
  if (CutsTheMap(reason) && sessions_->has_open_session(robot)) cut_sessions_.insert(robot);
  std::lock_guard lock(stats_mutex_);
  ++stats_.refusals_by_reason[RefusalName(reason)];
  if (!named) {
    ++stats_.rejected_unattributed;
    return;
  }
  ++stats_.robots[robot].rejected;
}

std::string FusionWorker::WhySessionIsNotKept(const RobotId& robot) const {
  if (cut_sessions_.count(robot) > 0) {
    return "a budget refused some of its tiles, so the server does not hold its map whole";
  }
  if (fusion_.TrustOf(robot).standing == fusion::Standing::kQuarantined) {
    return "it is quarantined, its map contradicts the fleet's";
  }
  return {};
}

void FusionWorker::Admit(transport::TileEvent event, Timestamp now,
                         std::chrono::steady_clock::time_point steady) {
  const RobotId robot = event.tile.robot_id;
  const std::string participant =
      event.writer.empty() ? std::string() : RobotRegistry::ParticipantOf(event.writer);
  if (event.kind == transport::TileEvent::Kind::kRejected) {
    // Past the decode limits (a zstd bomb, a million vertices): refused before it was inflated.
    const bool too_large = event.error.code() == StatusCode::kResourceExhausted;
    Refuse(robot, too_large ? Refusal::kDecodedSize : Refusal::kMalformed, event.error.message(),
           participant);
    return;
  }
  if (auto refused = TileAdmission::CheckRobotId(event.tile)) {
    Refuse(robot, refused->reason, refused->detail, participant);
    return;
  }
  // A tile its writer may not send for this robot id, refused naming both and why.
  const auto refuse_sender = [&](Refusal reason, const char* which) {
    Refuse(robot, reason,
           fmt::format("tile ({}, {}) for robot {} from participant {}, which {}",
                       event.tile.tile.x, event.tile.tile.y, robot.value, participant, which),
           participant);
  };
  switch (registry_->WhoSpeaks(robot, event.writer)) {
    case RobotRegistry::Speaker::kOther:
      refuse_sender(Refusal::kNotOwner, "does not own it");
      return;
    case RobotRegistry::Speaker::kNotItself:
      refuse_sender(Refusal::kNotItself, "authenticated as another identity");
      return;
    case RobotRegistry::Speaker::kOverCap:
      refuse_sender(Refusal::kTooManyIds, "already speaks for as many robots as a participant may");
      return;
    case RobotRegistry::Speaker::kUnclaimed:
      // Its status (and with it, who owns the id) may still be on its way: held, bounded.
      if (auto refused = held_.Hold(std::move(event), participant, steady)) {
        Refuse(robot, refused->reason, refused->detail, participant);
      }
      return;
    case RobotRegistry::Speaker::kOwner:
      break;
  }
  if (event.kind == transport::TileEvent::Kind::kRemoved) {
    RemoveTile(robot, event.tile.tile);
    return;
  }
  TileAdmission::Verdict verdict =
      admission_.Admit(event.tile, event.serialized_bytes,
                       TileBudget::Source{robot, participant, event.host}, now, steady);
  if (const auto* refused = std::get_if<TileAdmission::Refused>(&verdict)) {
    Refuse(robot, refused->reason, refused->detail, participant);
    return;
  }
  auto& admitted = std::get<TileAdmission::Admitted>(verdict);
  for (const RobotId& newer : admitted.evict) EvictRobot(newer);
  const TileId key = event.tile.tile;
  // Ids of one participant share its place in the queue; a tile without a writer pays as its id.
  const std::string payer = participant.empty() ? "robot " + robot.value : participant;
  queue_.Push(payer, {robot, key},
              PendingTile{std::move(event.tile), admitted.evidence_stamp, event.serialized_bytes});
}

void FusionWorker::EvictRobot(const RobotId& robot) {
  const size_t queued = queue_.EraseIf([&](const auto& key) { return key.first == robot; });
  const std::vector<TileId> tiles = admission_.DropRobot(robot);
  for (const TileId& tile : tiles) DropTileData(robot, tile);
  Refuse(robot, Refusal::kMemoryBudget,
         fmt::format("the server's memory budget for all robots' tiles is spent: robot {}, "
                     "claimed after the robots that need it, gives way ({} tiles and {} queued "
                     "dropped)",
                     robot.value, tiles.size(), queued));
  // Large frees go back to the system, not only to the allocator's free lists.
  ReturnFreedMemory();
}

void FusionWorker::HandleAdmissions() {
  for (transport::RobotAdmissionEvent& event : admission_reader_->Drain()) {
    if (event.kind == transport::RobotAdmissionEvent::Kind::kRejected) {
      spdlog::warn("server: refused an admission: {}", event.error.message());
      continue;
    }
    if (event.kind != transport::RobotAdmissionEvent::Kind::kSample) continue;
    const transport::RobotAdmissionMessage& admission = event.message;
    const bool quarantined =
        fusion_.TrustOf(admission.robot).standing == fusion::Standing::kQuarantined;
    if (!fusion_.AdmitRobot(admission.robot)) continue;  // admitted before: nothing changes
    StoreAdmission(admission);
    spdlog::warn("server: robot {} admitted by {}{}; its tiles are fused from now on",
                 admission.robot.value,
                 admission.operator_name.empty() ? "an operator" : admission.operator_name,
                 quarantined ? " out of quarantine" : " (it was not quarantined)");
  }
}

void FusionWorker::StoreAdmission(const transport::RobotAdmissionMessage& admission) {
  if (store_ == nullptr) return;
  const int64_t now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  const Status stored = store_->PutAdmission({admission.robot, admission.operator_name, now_ns});
  if (!stored.ok()) {
    // It holds until this server stops; the operator is told it will not outlive a restart.
    spdlog::error(
        "server: map store: the admission of {} is not stored (it holds until the "
        "server stops): {}",
        admission.robot.value, stored.message());
    std::lock_guard lock(stats_mutex_);
    ++stats_.store_errors;
  }
}

void FusionWorker::ReportStandings() {
  std::vector<fusion::TrustReport> changes = fusion_.TakeTrustChanges();
  if (changes.empty()) return;
  for (const fusion::TrustReport& report : changes) {
    if (!report.standing_changed) {
      spdlog::debug("server: robot {} is still quarantined: {}", report.robot.value, report.reason);
    } else if (report.standing == fusion::Standing::kQuarantined) {
      spdlog::warn(
          "server: robot {} quarantined: {}, around ({:.1f}, {:.1f})..({:.1f}, {:.1f}) m; its "
          "tiles are kept, not fused, until its map agrees, another robot confirms the change, "
          "or an operator runs `fleetmap admit {}`",
          report.robot.value, report.reason, report.area_min.x(), report.area_min.y(),
          report.area_max.x(), report.area_max.y(), report.robot.value);
    } else if (report.standing == fusion::Standing::kTrusted) {
      spdlog::info("server: robot {} {}; its tiles are fused again", report.robot.value,
                   report.reason);
    }
    placer_->SetStanding(report);
  }
  std::lock_guard lock(stats_mutex_);
  for (fusion::TrustReport& report : changes) {
    if (report.standing_changed && report.standing == fusion::Standing::kQuarantined) {
      ++stats_.quarantines;
    }
    stats_.standings[report.robot] = std::move(report);
  }
}

void FusionWorker::NoteSource(const RobotId& robot) {
  const std::string owner = registry_->OwnerOf(robot);
  if (!owner.empty()) fusion_.SetRobotSource(robot, RobotRegistry::ParticipantOf(owner));
}

void FusionWorker::RemoveTile(const RobotId& robot, const TileId& tile) {
  queue_.EraseIf([&](const auto& key) { return key.first == robot && key.second == tile; });
  admission_.Forget(robot, tile);
  DropTileData(robot, tile);
}

void FusionWorker::DropTileData(const RobotId& robot, const TileId& tile) {
  if (registry_->TilesInMapFrame(robot)) {
    RefuseMapFrameRobot(robot, map_frames_.RemoveTile(robot, tile));
    return;
  }
  fusion_.RemoveRobotTile(robot, tile);
  RememberContribution(robot, tile);
  sessions_->RemoveTile(robot, tile);
}

void FusionWorker::ReleaseHeldTiles(std::chrono::steady_clock::time_point steady) {
  const auto claimed = [&](const RobotId& robot) { return !registry_->OwnerOf(robot).empty(); };
  const auto expired = [&](const RobotId& robot, const TileId& tile) {
    Refuse(robot, Refusal::kUnclaimed,
           fmt::format(
               "tile ({}, {}) waited {} s for a status claiming robot {}; dropped", tile.x, tile.y,
               std::chrono::duration_cast<std::chrono::seconds>(options_.unclaimed_wait).count(),
               robot.value));
  };
  const Timestamp now = Clock::now();
  // Admit() sorts the owner's tiles from the others now that the id is claimed.
  for (transport::TileEvent& event : held_.Release(steady, claimed, expired)) {
    Admit(std::move(event), now, steady);
  }
}

void FusionWorker::FuseQueuedTiles(std::chrono::steady_clock::duration budget) {
  const auto start = std::chrono::steady_clock::now();
  // Stop() does not wait for a backlog: the round ends after the turn in progress.
  while (!queue_.empty() && std::chrono::steady_clock::now() - start < budget &&
         !thread_.stopping()) {
    // What arrived during the last turn joins the queue now, not after the slice: an honest
    // update waits for at most the turn in progress.
    HandleTileEvents();
    std::string payer;
    const auto turn_start = std::chrono::steady_clock::now();
    std::vector<PendingTile> turn = queue_.NextTurn(kMaxTilesPerTurn, kTurnTarget, &payer);
    const size_t tiles = turn.size();
    for (PendingTile& pending : turn) {
      const RobotId robot = pending.tile.robot_id;
      ApplyTile(robot, std::move(pending));
    }
    // The turn's cost includes vectorizing what it changed: that is what delays the others.
    PublishFused(std::chrono::steady_clock::now());
    queue_.Charge(payer, std::chrono::steady_clock::now() - turn_start, tiles);
  }
}

void FusionWorker::ApplyTile(const RobotId& robot, PendingTile pending) {
  const transport::VectorTileMessage& tile = pending.tile;
  if (registry_->TilesInMapFrame(robot)) {
    ApplyMapFrameTile(robot, tile, pending.evidence_stamp);
    std::lock_guard lock(stats_mutex_);
    FusionStats::Robot& stats = stats_.robots[robot];
    ++stats.tiles;
    stats.bytes += pending.bytes;
    return;
  }
  NoteSource(robot);
  const Status updated =
      fusion_.UpdateRobotTile(robot, tile.tile, tile.map, pending.evidence_stamp);
  if (!updated.ok()) {
    Refuse(robot, Refusal::kMalformed,
           fmt::format("tile ({}, {}): {}", tile.tile.x, tile.tile.y, updated.message()));
    return;
  }
  sessions_->RecordTile(robot, tile.tile, tile.map, pending.evidence_stamp);
  if (store_ != nullptr) Remember(robot.value, tile);
  std::lock_guard lock(stats_mutex_);
  FusionStats::Robot& stats = stats_.robots[robot];
  ++stats.tiles;
  stats.bytes += pending.bytes;
}

void FusionWorker::HandleGrids() {
  for (GridUpdate& update : grids_.Drain()) {
    vector_map::TiledVectorizeOptions options;
    options.tile_size = options_.fusion.tile_size;
    // A grid whose frame is not known is tiled in its own frame and placed like tiles; so is one
    // whose given frame is rotated (fleet tiles are cut on the fleet frame's axis-aligned
    // cells), then carried into the fleet frame at that transform.
    const bool rotated = update.fleet_from_map && update.fleet_from_map->yaw != 0.0;
    const bool in_map_frame = !update.fleet_from_map || rotated;
    const Pose2 tiling_frame = in_map_frame ? Pose2{} : *update.fleet_from_map;
    const auto tiled =
        vector_map::VectorizeTiled(update.map.grid, tiling_frame.ToTransform(), options);
    if (!tiled.ok()) {
      spdlog::warn("server: cannot fuse the grid of {}: {}", update.robot.value,
                   tiled.status().message());
      std::lock_guard lock(stats_mutex_);
      ++stats_.robots[update.robot].rejected;
      continue;
    }
    if (in_map_frame) {
      if (rotated) GiveFrame(update.robot, *update.fleet_from_map);
      for (const auto& [tile, map] : tiled->tiles) {
        transport::VectorTileMessage message;
        message.robot_id = update.robot;
        message.tile = tile;
        message.stamp = update.map.stamp;
        message.tile_size = options_.fusion.tile_size;
        message.map = map;
        ApplyMapFrameTile(update.robot, message, update.map.stamp);
      }
      continue;
    }
    NoteSource(update.robot);
    for (const auto& [tile, map] : tiled->tiles) {
      const Status updated = fusion_.UpdateRobotTile(update.robot, tile, map, update.map.stamp);
      if (!updated.ok()) {
        spdlog::warn("server: {}: {}", update.robot.value, updated.message());
        continue;
      }
      sessions_->RecordTile(update.robot, tile, map, update.map.stamp);
      RememberContribution(update.robot, tile);
    }
  }
}

void FusionWorker::PublishFused(std::chrono::steady_clock::time_point now) {
  StatusOr<std::vector<fusion::FusedTile>> changed = fusion_.FuseChanged();
  ReportStandings();
  if (!changed.ok()) {
    spdlog::error("server: fusion failed: {}", changed.status().message());
    return;
  }
  uint64_t bytes = 0;
  for (fusion::FusedTile& tile : *changed) {
    transport::VectorTileMessage message;
    message.robot_id = RobotId{store::kFleetOwner};
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
  fused_revisions_ += changed->size();
  const bool serving = serving_.load();
  if (serving && !was_serving_) last_map_ = {};  // the new server's map goes out at once
  map_dirty_ = map_dirty_ || (serving && !was_serving_);
  was_serving_ = serving;
  bool map_sent = false;
  if (serving && map_dirty_ && now - last_map_ >= options_.map_period) {
    transport::MapMessage map;
    fusion::GridWindow shown;
    map.grid = fusion_.FusedGrid(&shown);
    // Said when tiles are first left out, and then at most every kWindowWarningPeriod while the
    // number changes: a peer spreading tiles far away changes it at every map period.
    const bool left_out_changed = shown.tiles_left_out != tiles_outside_map_;
    if (shown.tiles_left_out > 0 && left_out_changed &&
        (tiles_outside_map_ == 0 || now - last_window_warning_ >= kWindowWarningPeriod)) {
      last_window_warning_ = now;
      spdlog::warn(
          "server: the fused tiles span more than one grid of {} cells can show: "
          "rt/fleetmap/map shows tiles ({}, {})..({}, {}) ({} tiles) and leaves {} out; "
          "rt/fleetmap/fused_tiles carries them all",
          options_.fusion.max_grid_cells, shown.rect.min.x, shown.rect.min.y, shown.rect.max.x,
          shown.rect.max.y, shown.tiles_shown, shown.tiles_left_out);
    }
    tiles_outside_map_ = shown.tiles_left_out;
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

Status FusionWorkerOptions::Validate() const {
  if (store_lock_timeout.count() < 0) {
    return InvalidArgumentError("fusion worker options: store_lock_timeout " +
                                std::to_string(store_lock_timeout.count()) + " ms is negative");
  }
  FLEETMAP_RETURN_IF_ERROR(fusion.Validate());
  FLEETMAP_RETURN_IF_ERROR(placement.Validate());
  return admission.Validate();
}

void FusionWorkerOptions::Describe(OptionsPrinter& out) const {
  out.Nested("fusion", fusion);
  out.Add("store_path", store_path);
  out.Add("history_rows", history_rows);
  out.Add("store_lock_timeout", store_lock_timeout);
  out.Add("map_period", map_period);
  out.Nested("admission", admission);
  out.Add("unclaimed_wait", unclaimed_wait);
  out.Nested("placement", placement);
}

void FusionWorker::ApplyMapFrameTile(const RobotId& robot, const transport::VectorTileMessage& tile,
                                     Timestamp stamp) {
  NoteSource(robot);
  RefuseMapFrameRobot(robot, map_frames_.UpdateTile(robot, tile.tile, tile.map, stamp));
  if (store_ == nullptr) return;
  // Kept in the store apart from the fleet-frame rows: the fused map is not rebuilt from them.
  transport::VectorTileMessage stored = tile;
  stored.robot_id = robot;
  Remember(store::MapFrameOwner(robot), stored);
}

void FusionWorker::RestoreMapFrameTiles(const std::vector<store::TileRecord>& rows) {
  size_t restored = 0;
  for (const store::TileRecord& row : rows) {
    const RobotId robot = *store::MapFrameRobot(row.owner);
    const std::string name = options_.store_path + ": map-frame tile " + row.owner + " (" +
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
    // Unplaced until registration places the robot again (its placement is not stored: it is
    // found again from the map, against the restored fleet map).
    map_frames_.UpdateTile(robot, tile->tile, std::move(tile->map), tile->stamp);
    admission_.Adopt(robot, tile->tile);
    placer_->Unplaced(robot);
    ++restored;
  }
  if (restored > 0) {
    spdlog::info("server: restored {} map-frame tiles of robots the server places", restored);
  }
}

void FusionWorker::RefuseMapFrameRobot(const RobotId& robot, const std::set<TileId>& changed) {
  for (const TileId& tile : changed) {
    std::optional<MapFrameRobots::FleetTile> contribution = map_frames_.Contribution(robot, tile);
    if (!contribution) {
      fusion_.RemoveRobotTile(robot, tile);
      sessions_->RemoveTile(robot, tile);
    } else if (const Status updated =
                   fusion_.UpdateRobotTile(robot, tile, contribution->map, contribution->stamp);
               !updated.ok()) {
      // Placed beyond the fleet map's range: that part of the robot's map is not fused.
      spdlog::warn("server: robot {}: {}", robot.value, updated.message());
      continue;
    } else {
      sessions_->RecordTile(robot, tile, contribution->map, contribution->stamp);
    }
    RememberContribution(robot, tile);
  }
}

void FusionWorker::HandlePlacements(std::chrono::steady_clock::time_point now) {
  for (const RobotFrameNote& note : frame_notes_.Drain()) {
    if (note.fleet_from_map) {
      GiveFrame(note.robot, *note.fleet_from_map);
    } else {
      placer_->Unplaced(note.robot);
    }
  }
  const auto placement_of = [this](const RobotId& robot) { return map_frames_.placement(robot); };
  for (const RobotPlacer::Decision& decision : placer_->Decide(placement_of)) {
    RefuseMapFrameRobot(decision.robot, map_frames_.Place(decision.robot, decision.fleet_from_map));
  }
  ScheduleRegistration(now);
  if (serving_.load()) placer_->PublishTf(now);
  std::lock_guard lock(stats_mutex_);
  stats_.frames = placer_->frames();
}

void FusionWorker::GiveFrame(const RobotId& robot, const Pose2& fleet_from_map) {
  placer_->Given(robot, fleet_from_map);
  // Tiles in its own map frame (a rotated given frame) are carried into the fleet frame at it,
  // exactly as a placement by registration would; fleet-frame tiles need nothing.
  if (registry_->TilesInMapFrame(robot) || map_frames_.Knows(robot)) {
    if (map_frames_.placement(robot) != fleet_from_map) {
      RefuseMapFrameRobot(robot, map_frames_.Place(robot, fleet_from_map));
    }
  }
}

std::optional<Pose2> FusionWorker::PlacementOf(const RobotId& robot) const {
  std::lock_guard lock(stats_mutex_);
  const auto frame = stats_.frames.find(robot);
  if (frame == stats_.frames.end() || !frame->second.placed()) return std::nullopt;
  return frame->second.fleet_from_map;
}

PlacementJob FusionWorker::MakePlacementJob(const RobotId& robot) const {
  PlacementJob job;
  job.robot = robot;
  job.resolution = options_.fusion.FusedResolution();
  job.map_changes = map_frames_.changes(robot);
  return job;
}

vector_map::VectorMap FusionWorker::GroupMap(const PlacementGroup& group) const {
  vector_map::VectorMap map = map_frames_.MapOf(group.root);
  for (const auto& [member, root_from_member] : group.root_from_member) {
    if (member == group.root) continue;
    map.Append(vector_map::Transformed(map_frames_.MapOf(member), root_from_member.ToTransform(),
                                       map.frame_id));
  }
  return map;
}

void FusionWorker::ScheduleRegistration(std::chrono::steady_clock::time_point now) {
  if (placer_->Busy()) return;
  const std::vector<RobotId> robots = map_frames_.robots();
  // With no frame known yet, the first robot with a map anchors the fleet frame.
  if (!placer_->AnyPlaced() && fusion_.contribution_count() == 0) {
    for (const RobotId& robot : robots) {
      if (map_frames_.tile_count(robot) == 0) continue;
      const RobotPlacer::Decision anchor = placer_->Anchor(robot);
      RefuseMapFrameRobot(robot, map_frames_.Place(robot, anchor.fleet_from_map));
      return;
    }
    return;
  }
  // Round robin from the robot after the last one registered: however many robots keep changing
  // their maps (a hostile peer's among them), none waits behind the others.
  std::vector<RobotId> turn = robots;
  std::rotate(turn.begin(), std::upper_bound(turn.begin(), turn.end(), last_registered_),
              turn.end());
  for (const RobotId& robot : turn) {
    if (map_frames_.tile_count(robot) == 0) continue;
    if (std::optional<PlacementJob> job = NextRegistration(robot, now)) {
      last_registered_ = robot;
      placer_->Submit(*std::move(job), now);
      return;
    }
  }
}

std::optional<PlacementJob> FusionWorker::NextRegistration(
    const RobotId& robot, std::chrono::steady_clock::time_point now) const {
  // 1. The robot's own map against the fleet map without it: to place it (unplaced) or to check
  //    its placement (placed).
  PlacementJob alone = MakePlacementJob(robot);
  alone.current = map_frames_.placement(robot);
  alone.target_changes = fused_revisions_;
  grid::OccupancyGrid fleet_map;  // rasterized once, when a registration on it is due
  const auto fleet_target = [&]() -> const grid::OccupancyGrid& {
    if (fleet_map.empty()) fleet_map = fusion_.FusedGrid(nullptr, &robot);
    return fleet_map;
  };
  if (placer_->Due(alone.key(), alone.map_changes, alone.target_changes, now)) {
    if (!HasOccupiedCell(fleet_target())) return std::nullopt;  // nothing to register on yet
    alone.target = fleet_target();
    alone.map = map_frames_.MapOf(robot);
    return alone;
  }
  if (alone.current) return std::nullopt;
  // 2. An unplaced robot registered to other unplaced ones: their maps merged in the root's frame
  //    (what they mapped together may meet the fleet map where no member's alone does). Only the
  //    root registers the group; placing it places the others (RobotPlacer::PlaceFollowers).
  const PlacementGroup group = placer_->GroupOf(robot);
  if (group.root == robot && group.root_from_member.size() > 1) {
    PlacementJob merged = alone;
    for (const auto& [member, unused] : group.root_from_member) {
      if (member == robot) continue;
      merged.group.push_back(member);
      merged.map_changes += map_frames_.changes(member);
    }
    if (placer_->Due(merged.key(), merged.map_changes, merged.target_changes, now) &&
        HasOccupiedCell(fleet_target())) {
      merged.target = fleet_target();
      merged.map = GroupMap(group);
      return merged;
    }
  }
  // 3. Not on the fleet map (yet): perhaps on another unplaced robot's, outside its group.
  for (const RobotId& other : placer_->UnplacedOthers(robot)) {
    PlacementJob pair = MakePlacementJob(robot);
    pair.target_robot = other;
    pair.target_changes = map_frames_.changes(other);
    if (map_frames_.tile_count(other) == 0 ||
        !placer_->Due(pair.key(), pair.map_changes, pair.target_changes, now)) {
      continue;
    }
    pair.map = map_frames_.MapOf(robot);
    pair.target_map = map_frames_.MapOf(other);
    return pair;
  }
  return std::nullopt;
}

}  // namespace fleetmap::server
