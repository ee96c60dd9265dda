#include "server/fusion_worker.hpp"

#include <spdlog/spdlog.h>

#include <malloc.h>

#include "common/transport/topics.hpp"
#include "server/fleet_map_log.hpp"

namespace fleetmap::server {

StatusOr<std::unique_ptr<FusionWorker>> FusionWorker::Create(
    transport::Participant& participant, const fusion::FleetMapOptions& map,
    const FusionWorkerOptions& options, std::shared_ptr<RobotRegistry> registry) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  FLEETMAP_ASSIGN_OR_RETURN(fusion::FleetMap fleet_map, fusion::FleetMap::Create(map));
  std::unique_ptr<FusionWorker> worker(
      new FusionWorker(options, std::move(fleet_map), std::move(registry)));
  FusionWorker& self = *worker;
  // The store first: a server refused its store (another holds it) never joins the topics.
  if (!options.store_path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(
        self.store_, FleetMapStore::Open(
                         {options.store_path, options.history_rows, options.store_lock_timeout}));
    FLEETMAP_RETURN_IF_ERROR(self.store_->Restore(self.map_));
  }
  self.sessions_ = std::make_unique<SessionKeeper>(map.fusion.tile_size,
                                                   self.store_ ? self.store_->store() : nullptr,
                                                   options.sessions_in_memory);
  FLEETMAP_RETURN_IF_ERROR(self.sessions_->Restore());
  self.stats_.sessions_finished = self.sessions_->finished_count();
  FLEETMAP_ASSIGN_OR_RETURN(
      self.intake_,
      TileIntake::Create(
          participant, map.admission, options.unclaimed_wait, self.registry_,
          self.thread_.wake_up(),
          [&self](const RobotId& robot, fusion::Refusal reason, const std::string& detail,
                  const std::string& sender) { self.Refuse(robot, reason, detail, sender); },
          options.shard
              ? std::optional<ShardTileScope>(ShardTileScope(*options.shard, map.fusion.tile_size))
              : std::nullopt));
  FLEETMAP_ASSIGN_OR_RETURN(
      self.publisher_,
      FleetPublisher::Create(participant,
                             {map.fusion.tile_size, map.fusion.max_grid_cells, options.map_period,
                              map.placement.tf_period,
                              options.shard ? transport::ShardMapTopic(options.shard->name)
                                            : transport::kFleetMapTopic}));
  FLEETMAP_ASSIGN_OR_RETURN(self.admission_reader_, transport::RobotAdmissionReader::Create(
                                                        participant, self.thread_.wake_up()));
  self.registrations_ =
      std::make_unique<RegistrationRunner>(map.placement.registration, self.thread_.wake_up());
  if (options.shard && options.shard->plan.regions().size() > 1) {
    FLEETMAP_ASSIGN_OR_RETURN(self.shard_frames_,
                              ShardFrames::Create(participant, self.thread_.wake_up()));
  }
  return worker;
}

FusionWorker::~FusionWorker() {
  Stop();
  // Readers and writers go before the participant that owns their topics (the caller's).
  intake_.reset();
  publisher_.reset();
  admission_reader_.reset();
}

void FusionWorker::SetListeners(FleetPublisher::MapListener on_fused_map,
                                SessionKeeper::Listener on_sessions) {
  publisher_->SetMapListener(std::move(on_fused_map));
  sessions_->SetListener(std::move(on_sessions));
}

void FusionWorker::Start() {
  sessions_->ReportRestored();
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

void FusionWorker::RecordRobot(store::RobotRecord robot) {
  robot_records_.Push(std::move(robot));
  thread_.Wake();
}

FusionStats FusionWorker::stats() const {
  FusionStats stats;
  {
    std::lock_guard lock(stats_mutex_);
    stats = stats_;
  }
  stats.tile_events_dropped = intake_->dropped();
  stats.grids_dropped = grids_.dropped();
  stats.robot_records_dropped = robot_records_.dropped();
  return stats;
}

std::optional<Pose2> FusionWorker::PlacementOf(const RobotId& robot) const {
  std::lock_guard lock(stats_mutex_);
  const auto frame = stats_.frames.find(robot);
  if (frame == stats_.frames.end() || !frame->second.placed()) return std::nullopt;
  return frame->second.fleet_from_map;
}

bool FusionWorker::Round() {
  HandleAdmissions();
  HandleFrameNotes();
  intake_->Drain(map_);
  // Bounded, so that new samples are drained (and a flood coalesced) while a backlog lasts.
  FuseQueuedTiles(kFusionSlice);
  HandleGrids();
  const auto now = std::chrono::steady_clock::now();
  HandlePlacements(now);
  Publish();
  publisher_->PublishDue(map_, serving_.load(), now);
  HandleRobotRecords();
  if (store_ != nullptr) store_->Flush(map_, now);
  {
    std::lock_guard lock(stats_mutex_);
    stats_.fused_tiles_published = publisher_->tiles_published();
    stats_.fused_bytes_published = publisher_->tile_bytes_published();
    stats_.maps_published = publisher_->maps_published();
    stats_.fused_tiles = map_.fusion().fused_tiles().size();
    if (store_ != nullptr) {
      stats_.store_errors = store_->errors();
      stats_.store_behind = store_->behind();
      stats_.store_pending = store_->pending();
    }
    stats_.sessions_finished = sessions_->finished_count();
    stats_.tiles_on_no_shard = intake_->tiles_on_no_shard();
    stats_.tiles_of_other_shards = intake_->tiles_of_other_shards();
  }
  // A backlog (fused or still to admit): the next round starts without waiting.
  return map_.HasQueued() || intake_->queued() > 0;
}

void FusionWorker::AtStop() {
  Publish();
  if (store_ != nullptr) store_->FinalFlush(map_);
}

void FusionWorker::FuseQueuedTiles(std::chrono::steady_clock::duration budget) {
  const auto start = std::chrono::steady_clock::now();
  // Stop() does not wait for a backlog: the round ends after the turn in progress.
  while (map_.HasQueued() && std::chrono::steady_clock::now() - start < budget &&
         !thread_.stopping()) {
    // What arrived during the last turn joins the queue now, not after the slice: an honest
    // update waits for at most the turn in progress.
    intake_->Drain(map_);
    map_.FuseTurn();
    Publish();
  }
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
        map_.TrustOf(admission.robot).standing == fusion::Standing::kQuarantined;
    if (!map_.AdmitRobot(admission.robot)) continue;  // admitted before: nothing changes
    if (store_ != nullptr) store_->KeepAdmission(admission);
    spdlog::warn("server: robot {} admitted by {}{}; its tiles are fused from now on",
                 admission.robot.value,
                 admission.operator_name.empty() ? "an operator" : admission.operator_name,
                 quarantined ? " out of quarantine" : " (it was not quarantined)");
  }
}

void FusionWorker::HandleFrameNotes() {
  for (const RobotFrameNote& note : frame_notes_.Drain())
    map_.Join(note.robot, note.fleet_from_map);
  if (shard_frames_) shard_frames_->FollowInto(map_);
}

void FusionWorker::HandleGrids() {
  for (GridUpdate& update : grids_.Drain()) {
    const std::string owner = registry_->OwnerOf(update.robot);
    const Status applied =
        map_.ApplyGrid(update.robot, update.map.grid, update.map.stamp, update.fleet_from_map,
                       owner.empty() ? std::string() : RobotRegistry::ParticipantOf(owner));
    if (!applied.ok()) {
      spdlog::warn("server: cannot fuse the grid of {}: {}", update.robot.value, applied.message());
      std::lock_guard lock(stats_mutex_);
      ++stats_.robots[update.robot].rejected;
    }
  }
}

void FusionWorker::HandlePlacements(std::chrono::steady_clock::time_point now) {
  for (const registration::PlacementResult& result : registrations_->Results()) {
    map_.Placed(result, now);
  }
  if (std::optional<registration::PlacementJob> job = map_.NextRegistration(now)) {
    registrations_->Submit(*std::move(job));
  }
}

void FusionWorker::HandleRobotRecords() {
  std::vector<store::RobotRecord> records = robot_records_.Drain();
  if (records.empty()) return;
  const size_t errors = sessions_->RobotsChanged(records, map_);
  if (store_ != nullptr) {
    for (store::RobotRecord& robot : records) store_->KeepRobot(std::move(robot));
  }
  std::lock_guard lock(stats_mutex_);
  stats_.store_errors += errors;
}

void FusionWorker::Publish() {
  fusion::FleetMapChanges changes = map_.TakeChanged();
  for (const Notice& notice : changes.notices) LogNotice(notice);
  for (const fusion::DroppedTiles& dropped : changes.dropped) {
    Refuse(dropped.robot, dropped.reason, dropped.detail);
  }
  // Large frees (a robot's evicted tiles) go back to the system, not only to the allocator's
  // free lists: glibc keeps freed heap below its top otherwise, and the RSS would not go down.
  if (!changes.evicted.empty()) malloc_trim(0);
  for (const fusion::ContributionChange& change : changes.contributions) sessions_->Follow(change);
  const std::vector<transport::VectorTileMessage> fused =
      publisher_->PublishTiles(std::move(changes.fused));
  publisher_->PublishFrames(changes.frames);
  if (store_ != nullptr) store_->Keep(changes, fused);
  ReportStandings(changes.standings);
  std::lock_guard lock(stats_mutex_);
  for (const fusion::ReceivedTile& received : changes.received) {
    if (received.wire_bytes == 0) continue;  // cut from a grid, not received as a tile
    FusionStats::Robot& robot = stats_.robots[received.tile.robot_id];
    ++robot.tiles;
    robot.bytes += received.wire_bytes;
  }
  if (!changes.frames.empty()) stats_.frames = map_.frames();
}

void FusionWorker::ReportStandings(const std::vector<fusion::TrustReport>& standings) {
  if (standings.empty()) return;
  for (const fusion::TrustReport& report : standings) LogStanding(report);
  std::lock_guard lock(stats_mutex_);
  for (const fusion::TrustReport& report : standings) {
    if (report.standing_changed && report.standing == fusion::Standing::kQuarantined) {
      ++stats_.quarantines;
    }
    stats_.standings[report.robot] = report;
  }
}

void FusionWorker::Refuse(const RobotId& robot, fusion::Refusal reason, const std::string& detail,
                          const std::string& sender) {
  // A name that is not a robot name (empty, too long) is not used as a key anywhere.
  const bool named = IsValidRobotName(robot.value);
  refusals_.RefuseFrom(sender, named ? robot.value : std::string(), reason, detail);
  if (named) sessions_->Refused(robot, reason);
  std::lock_guard lock(stats_mutex_);
  ++stats_.refusals_by_reason[RefusalName(reason)];
  if (!named) {
    ++stats_.rejected_unattributed;
    return;
  }
  ++stats_.robots[robot].rejected;
}

Status FusionWorkerOptions::Validate() const {
  if (store_lock_timeout.count() < 0) {
    return InvalidArgumentError("fusion worker options: store_lock_timeout " +
                                std::to_string(store_lock_timeout.count()) + " ms is negative");
  }
  return Status::Ok();
}

void FusionWorkerOptions::Describe(OptionsPrinter& out) const {
  out.Add("store_path", store_path);
  out.Add("history_rows", history_rows);
  out.Add("store_lock_timeout", store_lock_timeout);
  out.Add("map_period", map_period);
  out.Add("unclaimed_wait", unclaimed_wait);
  out.Add("sessions_in_memory", sessions_in_memory);
  if (shard) out.Add("shard", shard->name);
}

}  // namespace fleetmap::server
