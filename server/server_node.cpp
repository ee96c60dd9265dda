#include "server/server_node.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "common/scene/entity_frames.hpp"
#include "common/transport/topics.hpp"

namespace fleetmap::server {

const char* RobotStateName(RobotRecord::State state) {
  switch (state) {
    case RobotRecord::State::kActive:
      return "active";
    case RobotRecord::State::kLeft:
      return "left";
    case RobotRecord::State::kLost:
      return "lost";
  }
  return "unknown";
}

namespace {

store::RobotRecord RobotRecordFor(const RobotId& robot, const std::string& state) {
  const int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  return store::RobotRecord{robot, now, now, state, ""};
}

}  // namespace

Status ServerOptions::Validate() const {
  if (duration.count() < 0) return InvalidArgumentError("--duration must be >= 0");
  if (max_robots_per_participant == 0) {
    return InvalidArgumentError("--max-robots-per-participant must be >= 1");
  }
  if (ownership_strength < 0) return InvalidArgumentError("--ownership-strength must be >= 0");
  if (shard && shard->plan.Find(shard->name) == nullptr) {
    return InvalidArgumentError("--shard " + shard->name + " is not in the shard plan");
  }
  if (shard && shard->region().Tiles(map.fusion.tile_size).empty()) {
    return InvalidArgumentError("--shard " + shard->name +
                                ": its region holds no tile's centre (tiles of " +
                                std::to_string(map.fusion.tile_size) + " m)");
  }
  FLEETMAP_RETURN_IF_ERROR(map.Validate());
  FLEETMAP_RETURN_IF_ERROR(worker.Validate());
  // A part that is switched off is not made, so its options are not checked.
  if (learning.enabled) {
    FLEETMAP_RETURN_IF_ERROR(learning.Validate().WithContext("object learning"));
  }
  if (prediction.enabled) {
    FLEETMAP_RETURN_IF_ERROR(prediction.Validate().WithContext("map extrapolation"));
  }
  if (route_graph.enabled) FLEETMAP_RETURN_IF_ERROR(route_graph.Validate());
  return Status::Ok();
}

StatusOr<std::unique_ptr<ServerNode>> ServerNode::Create(ServerOptions options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  if (options.shard) {
    options.map.shard = options.shard;
    options.worker.shard = options.shard;
  }
  std::unique_ptr<ServerNode> node(new ServerNode(std::move(options)));
  node->registry_ = std::make_shared<RobotRegistry>(node->options_.max_robots_per_participant);
  transport::ParticipantOptions dds = node->options_.dds;
  dds.name = "fleetmap-server";
  dds.ownership_strength = node->options_.ownership_strength;
  FLEETMAP_ASSIGN_OR_RETURN(node->participant_, transport::Participant::Create(dds));
  if (node->participant_->secured()) {
    // The registry outlives no reader: the workers that consult it go before the participant.
    const transport::Participant* participant = node->participant_.get();
    node->registry_->RequireIdentity([participant](const std::string& writer) {
      return participant->AuthenticatedName(writer);
    });
  }
  dds.name = "fleetmap-server-status";
  FLEETMAP_ASSIGN_OR_RETURN(node->status_participant_, transport::Participant::Create(dds));
  FLEETMAP_ASSIGN_OR_RETURN(node->status_reader_, transport::RobotStatusReader::Create(
                                                      *node->status_participant_, node->wake_up_));
  FLEETMAP_ASSIGN_OR_RETURN(
      node->presence_,
      FleetPresence::Create(*node->status_participant_, *node->participant_,
                            FleetPresence::Identity{node->participant_->id(), node->ServerName(),
                                                    node->options_.ownership_strength,
                                                    node->ShardName(), node->ShardRegion()},
                            node->wake_up_));
  // The sessions in memory are the learner's input: as many as it reads.
  node->options_.worker.sessions_in_memory = node->options_.learning.max_sessions;
  FLEETMAP_ASSIGN_OR_RETURN(node->fusion_worker_,
                            FusionWorker::Create(*node->participant_, node->options_.map,
                                                 node->options_.worker, node->registry_));
  if (node->options_.learning.enabled) {
    FLEETMAP_ASSIGN_OR_RETURN(
        node->learning_worker_,
        ObjectLearningWorker::Create(*node->participant_, node->options_.learning,
                                     node->options_.map.fusion,
                                     PublishedIds::For(node->options_.shard)));
  }
  if (node->options_.prediction.enabled) {
    FLEETMAP_ASSIGN_OR_RETURN(
        node->prediction_worker_,
        PredictionWorker::Create(*node->participant_, node->options_.prediction,
                                 PublishedIds::For(node->options_.shard)));
    FLEETMAP_ASSIGN_OR_RETURN(node->entity_reader_,
                              transport::EntityReader::Create(*node->participant_, node->wake_up_));
  }
  if (node->options_.route_graph.enabled) {
    FLEETMAP_ASSIGN_OR_RETURN(
        node->route_graph_worker_,
        RouteGraphWorker::Create(*node->participant_, node->options_.route_graph,
                                 PublishedIds::For(node->options_.shard)));
  }
  ObjectLearningWorker* learning = node->learning_worker_.get();
  PredictionWorker* prediction = node->prediction_worker_.get();
  RouteGraphWorker* route_graph = node->route_graph_worker_.get();
  if (route_graph != nullptr && prediction != nullptr) {
    prediction->SetListener(
        [route_graph](const scene::SubmapNode& submap, const scene::DoorEntity* door,
                      bool withdrawn) { route_graph->SubmitSubmap(submap, door, withdrawn); });
  }
  if (route_graph != nullptr && learning != nullptr) {
    learning->SetListener([route_graph](const std::vector<transport::ObjectModelMessage>& objects) {
      route_graph->SubmitObjects(objects);
    });
  }
  node->fusion_worker_->SetListeners(
      [prediction, route_graph](const grid::OccupancyGrid& fused) {
        if (prediction != nullptr) prediction->SubmitMap(fused);
        if (route_graph != nullptr) route_graph->SubmitMap(fused);
      },
      [learning](std::vector<MappingSession> finished) {
        if (learning != nullptr) learning->Submit(std::move(finished));
      });
  return node;
}

std::string ServerNode::ShardName() const {
  return options_.shard ? options_.shard->name : std::string();
}

std::array<double, 4> ServerNode::ShardRegion() const {
  if (!options_.shard) return {};
  const fleetmap::ShardRegion& region = options_.shard->region();
  return {region.min_x, region.min_y, region.max_x, region.max_y};
}

std::string ServerNode::ServerName() const {
  if (!options_.name.empty()) return options_.name;
  char host[256] = {};
  if (gethostname(host, sizeof(host) - 1) != 0) host[0] = '\0';
  return fmt::format("{}:{}", host[0] != '\0' ? host : "localhost", getpid());
}

Status ServerNode::Run(const std::atomic<bool>& stop) {
  spdlog::info("server: listening on DDS domain {}{}", participant_->domain_id(),
               participant_->localhost_only() ? " (localhost only)" : "");
  if (learning_worker_) learning_worker_->Start();
  if (prediction_worker_) prediction_worker_->Start();
  if (route_graph_worker_) route_graph_worker_->Start();
  // It serves once it has listened for a stronger server (FleetPresence).
  fusion_worker_->SetServing(false);
  fusion_worker_->Start();
  const auto start = std::chrono::steady_clock::now();
  while (!stop.load()) {
    const auto now = std::chrono::steady_clock::now();
    if (options_.duration.count() > 0 && now - start >= options_.duration) break;
    if (presence_->Tick(now, static_cast<uint32_t>(robots_.size()))) {
      fusion_worker_->SetServing(presence_->serving());
    }
    wake_up_->WaitFor(std::chrono::milliseconds(100));
    HandleRobotEvents();
    HandleMaps();
    HandleEntities();
    SubmitEntitiesOfPlacedRobots();
  }
  // Withdrawn first: a standby takes over while this one finishes.
  presence_.reset();
  fusion_worker_->Stop();
  if (prediction_worker_) prediction_worker_->Stop();
  if (route_graph_worker_) route_graph_worker_->Stop();
  if (learning_worker_) learning_worker_->Stop();
  PrintSummary(fusion_worker_->stats());
  // Readers and writers go before the participant that owns their topics.
  fusion_worker_.reset();
  prediction_worker_.reset();
  learning_worker_.reset();
  route_graph_worker_.reset();
  entity_reader_.reset();
  for (auto& [robot, record] : robots_) record.map_feed.reset();
  status_reader_.reset();
  return Status::Ok();
}

void ServerNode::HandleRobotEvents() {
  for (const transport::RobotEvent& event : status_reader_->Drain()) {
    switch (event.kind) {
      case transport::RobotEvent::Kind::kStatus:
        OnRobotAlive(event.status, event.writer);
        break;
      case transport::RobotEvent::Kind::kLeft:
        OnRobotGone(event.robot, RobotRecord::State::kLeft, event.writer);
        break;
      case transport::RobotEvent::Kind::kLost:
        OnRobotGone(event.robot, RobotRecord::State::kLost, event.writer);
        break;
      case transport::RobotEvent::Kind::kRejected:
        refusals_.Refuse("", fusion::Refusal::kMalformed,
                         "a robot status sample: " + event.error.message());
        break;
    }
  }
}

void ServerNode::OnRobotAlive(const RobotStatus& status, const std::string& writer) {
  const RobotRegistry::Claim claim =
      registry_->ClaimRobot(status.robot, writer, status.tiles_in_map_frame);
  if (claim == RobotRegistry::Claim::kClash) {
    ++robots_[status.robot].id_clashes;
    refusals_.RefuseFrom(RobotRegistry::ParticipantOf(writer), status.robot.value,
                         fusion::Refusal::kNotOwner,
                         fmt::format("a status from participant {} claims robot id {}, which "
                                     "participant {} owns: keeping the first, ignoring the other",
                                     RobotRegistry::ParticipantOf(writer), status.robot.value,
                                     registry_->OwnerOf(status.robot)));
    return;
  }
  if (claim == RobotRegistry::Claim::kNotItself) {
    const std::optional<std::string> name = participant_->AuthenticatedName(writer);
    refusals_.RefuseFrom(
        RobotRegistry::ParticipantOf(writer), status.robot.value, fusion::Refusal::kNotItself,
        fmt::format("a status from participant {}, authenticated as {}, claims robot "
                    "id {}: a participant speaks only for the robot it is enrolled "
                    "as",
                    RobotRegistry::ParticipantOf(writer),
                    name ? "\"" + *name + "\"" : std::string("nobody"), status.robot.value));
    return;
  }
  if (claim == RobotRegistry::Claim::kTooMany) {
    refusals_.RefuseFrom(RobotRegistry::ParticipantOf(writer), status.robot.value,
                         fusion::Refusal::kTooManyIds,
                         fmt::format("participant {} already speaks for {} robots; its claim of {} "
                                     "is ignored",
                                     RobotRegistry::ParticipantOf(writer),
                                     options_.max_robots_per_participant, status.robot.value));
    return;
  }
  RobotRecord& record = robots_[status.robot];
  // New, or back after it left or was lost.
  const bool joining =
      record.last_status.robot.value.empty() || record.state != RobotRecord::State::kActive;
  record.state = RobotRecord::State::kActive;
  record.last_status = status;
  const std::optional<Wire> grid_wire = RobotMapFeed::WireOf(status.robot, status.map_topic);
  if (grid_wire && record.map_feed == nullptr) {
    auto feed = RobotMapFeed::Create(*participant_, status.robot, *grid_wire, wake_up_);
    if (!feed.ok()) {
      spdlog::error("server: robot {} is on the {} wire but its map cannot be read: {}",
                    status.robot.value, WireName(*grid_wire), feed.status().message());
    } else {
      record.map_feed = std::move(feed).value();
    }
  }
  const auto configured = options_.transforms.find(status.robot);
  if (!grid_wire && status.fleet_from_map_given && configured != options_.transforms.end() &&
      !(configured->second == status.fleet_from_map) && !record.transform_mismatch_reported) {
    record.transform_mismatch_reported = true;
    spdlog::warn(
        "server: robot {} tiles its map with fleet_from_map ({}, {}, {}) but the "
        "transforms file says ({}, {}, {})",
        status.robot.value, status.fleet_from_map.x, status.fleet_from_map.y,
        status.fleet_from_map.yaw, configured->second.x, configured->second.y,
        configured->second.yaw);
  }
  if (const auto early = early_entities_.find(status.robot); early != early_entities_.end()) {
    for (auto& [entity_writer, entity] : early->second) {
      if (registry_->WhoSpeaks(status.robot, entity_writer) == RobotRegistry::Speaker::kOwner) {
        SubmitEntity(std::move(entity), record);
      } else {
        ++rejected_entities_;
        refusals_.RefuseFrom(RobotRegistry::ParticipantOf(entity_writer), status.robot.value,
                             fusion::Refusal::kNotOwner,
                             "an entity sent for robot " + status.robot.value +
                                 " before its owner claimed it, by another participant");
      }
    }
    early_entities_.erase(early);
  }
  if (!joining) return;
  fusion_worker_->RecordRobot(RobotRecordFor(status.robot, "active"));
  // A robot that does not know its frame is placed by the fusion worker, which may have done so
  // already (its tiles can come first): never note its placement back as given.
  const std::optional<Pose2> fleet_from_map = GivenFrame(record);
  fusion_worker_->NoteRobotFrame(status.robot, fleet_from_map);
  spdlog::info("server: robot {} joined ({} wire, map {} x {} at {:.3f} m, fleet_from_map {})",
               status.robot.value, grid_wire ? WireName(*grid_wire) : "tiles", status.map_width,
               status.map_height, status.map_resolution,
               fleet_from_map ? fmt::format("({:.2f}, {:.2f}, {:.3f} rad)", fleet_from_map->x,
                                            fleet_from_map->y, fleet_from_map->yaw)
                              : std::string("unknown: the server places its map frame"));
}

void ServerNode::OnRobotGone(const RobotId& robot, RobotRecord::State state,
                             const std::string& writer) {
  const auto it = robots_.find(robot);
  if (it == robots_.end() || it->second.state != RobotRecord::State::kActive) return;
  if (registry_->WhoSpeaks(robot, writer) != RobotRegistry::Speaker::kOwner) {
    // A second agent with this id went away, or a peer disposed an instance it does not own.
    refusals_.RefuseFrom(
        RobotRegistry::ParticipantOf(writer), robot.value, fusion::Refusal::kNotOwner,
        fmt::format("participant {} {} robot {}, which participant {} owns: ignored",
                    RobotRegistry::ParticipantOf(writer),
                    state == RobotRecord::State::kLeft ? "disposed" : "lost", robot.value,
                    registry_->OwnerOf(robot)));
    return;
  }
  RobotRecord& record = it->second;
  HandleMaps();  // keep whatever the robot sent before it went
  record.state = state;
  record.map_feed.reset();
  registry_->Release(robot, writer);
  fusion_worker_->RecordRobot(RobotRecordFor(robot, RobotStateName(state)));
  if (state == RobotRecord::State::kLost) {
    spdlog::warn("server: robot {} lost (no liveliness within {} ms); its map stays, marked stale",
                 robot.value, transport::kRobotLivelinessLease.count());
  } else {
    spdlog::info("server: robot {} left the fleet; its map stays, marked stale", robot.value);
  }
}

std::optional<Pose2> ServerNode::GivenFrame(const RobotRecord& record) const {
  const RobotStatus& status = record.last_status;
  if (const auto configured = options_.transforms.find(status.robot);
      configured != options_.transforms.end()) {
    return configured->second;
  }
  // An agent cutting tiles in its own map frame says whether its frame is given (a rotation) or
  // must be placed (--unplaced); an older agent's fleet-frame tiles mean a given frame.
  if (status.fleet_from_map_given || !status.tiles_in_map_frame) return status.fleet_from_map;
  return std::nullopt;
}

std::optional<Pose2> ServerNode::FleetFromMap(const RobotRecord& record) const {
  if (record.last_status.tiles_in_map_frame) {
    return fusion_worker_->PlacementOf(record.last_status.robot);
  }
  return GivenFrame(record);
}

void ServerNode::HandleMaps() {
  for (auto& [robot, record] : robots_) {
    if (record.map_feed == nullptr) continue;
    RobotMapFeed::Received received = record.map_feed->Poll();
    for (const Status& error : received.refused) {
      ++record.rejected_samples;
      // Through the refusal log: a peer flooding bad samples must not flood the log too.
      refusals_.Refuse(
          robot.value, fusion::Refusal::kMalformed,
          fmt::format("dropped a map sample from {}: {}", robot.value, error.message()));
    }
    record.maps_received += received.maps;
    record.updates_received += received.updates;
    record.bytes_received += received.bytes;
    if (!received.grid) continue;
    spdlog::info(
        "server: map from {}: {} x {} cells at {:.3f} m ({} whole, {} updates, {} bytes; total {} "
        "bytes)",
        robot.value, received.grid->grid.width(), received.grid->grid.height(),
        received.grid->grid.resolution(), received.maps, received.updates, received.bytes,
        record.bytes_received);
    // A robot that does not know its frame is placed from its own frame, like tiles.
    fusion_worker_->SubmitGrid(robot, std::move(*received.grid), GivenFrame(record));
  }
}

void ServerNode::HandleEntities() {
  if (entity_reader_ == nullptr) return;
  for (transport::EntityEvent& event : entity_reader_->Drain()) {
    const RobotId& robot = event.message.robot;
    if (event.kind == transport::EntityEvent::Kind::kRejected) {
      ++rejected_entities_;
      spdlog::warn("server: dropped an entity: {}", event.error.message());
      continue;
    }
    const RobotRegistry::Speaker speaker = registry_->WhoSpeaks(robot, event.writer);
    if (speaker == RobotRegistry::Speaker::kOverCap) {
      ++rejected_entities_;
      refusals_.RefuseFrom(RobotRegistry::ParticipantOf(event.writer), robot.value,
                           fusion::Refusal::kTooManyIds,
                           fmt::format("entity {} for robot {} from participant {}, which already "
                                       "speaks for {} robots",
                                       event.message.entity_id(), robot.value,
                                       RobotRegistry::ParticipantOf(event.writer),
                                       options_.max_robots_per_participant));
      continue;
    }
    if (speaker == RobotRegistry::Speaker::kOther ||
        speaker == RobotRegistry::Speaker::kNotItself) {
      const bool itself = speaker == RobotRegistry::Speaker::kOther;
      ++rejected_entities_;
      refusals_.RefuseFrom(
          RobotRegistry::ParticipantOf(event.writer), robot.value,
          itself ? fusion::Refusal::kNotOwner : fusion::Refusal::kNotItself,
          fmt::format("entity {} for robot {} from participant {}, which {}",
                      event.message.entity_id(), robot.value,
                      RobotRegistry::ParticipantOf(event.writer),
                      itself ? "does not own it" : "authenticated as another identity"));
      continue;
    }
    if (event.kind == transport::EntityEvent::Kind::kRemoved) {
      prediction_worker_->RemoveEntity(robot, event.message.entity_id());
      continue;
    }
    const auto record = robots_.find(robot);
    if (speaker == RobotRegistry::Speaker::kUnclaimed || record == robots_.end() ||
        record->second.last_status.robot.value.empty()) {
      // Its fleet_from_map comes with its status: keep the entity until then (bounded).
      if (early_entities_.size() >= kMaxEarlyRobots && early_entities_.count(robot) == 0) {
        ++rejected_entities_;
        refusals_.RefuseFrom(RobotRegistry::ParticipantOf(event.writer), robot.value,
                             fusion::Refusal::kUnclaimed,
                             "an entity for a robot id no status claims (too many such ids)");
        continue;
      }
      auto& early = early_entities_[robot];
      if (early.size() < 1024) early.emplace_back(event.writer, std::move(event.message));
      continue;
    }
    SubmitEntity(std::move(event.message), record->second);
  }
}

void ServerNode::SubmitEntity(transport::EntityMessage entity, const RobotRecord& record) {
  const std::optional<Pose2> fleet_from_map = FleetFromMap(record);
  if (!fleet_from_map) {
    // Not placed yet: kept (bounded) until the server places the robot's map frame.
    auto& waiting = awaiting_placement_[entity.robot];
    if (waiting.size() < kMaxEntitiesAwaitingPlacement) waiting.push_back(std::move(entity));
    return;
  }
  entity.entity = ToFleetFrame(entity.entity, fleet_from_map->ToTransform());
  entity.frame_id = "fleet";
  prediction_worker_->SubmitEntity(std::move(entity));
}

void ServerNode::SubmitEntitiesOfPlacedRobots() {
  for (auto it = awaiting_placement_.begin(); it != awaiting_placement_.end();) {
    const auto record = robots_.find(it->first);
    if (record == robots_.end() || !FleetFromMap(record->second)) {
      ++it;
      continue;
    }
    for (transport::EntityMessage& entity : it->second) {
      SubmitEntity(std::move(entity), record->second);
    }
    it = awaiting_placement_.erase(it);
  }
}

void ServerNode::PrintSummary(const FusionStats& fusion) const {
  fmt::print("\n{:<16} {:<8} {:>7} {:>6} {:>12} {:>9} {:>8}  {}\n", "robot", "state", "tiles",
             "maps", "bytes in", "rejected", "clashes", "map frame in the fleet");
  for (const auto& [robot, record] : robots_) {
    const auto tiles = fusion.robots.find(robot);
    const FusionStats::Robot counts =
        tiles == fusion.robots.end() ? FusionStats::Robot{} : tiles->second;
    const auto frame = fusion.frames.find(robot);
    const std::string placement =
        frame == fusion.frames.end() ? std::string("-")
        : !frame->second.placed()
            ? std::string(RobotFrameStateName(frame->second.state))
            : fmt::format("{} ({:.2f}, {:.2f}, {:.1f} deg)",
                          RobotFrameStateName(frame->second.state), frame->second.fleet_from_map.x,
                          frame->second.fleet_from_map.y,
                          frame->second.fleet_from_map.yaw * 180.0 / M_PI);
    fmt::print("{:<16} {:<8} {:>7} {:>6} {:>12} {:>9} {:>8}  {}\n", robot.value,
               RobotStateName(record.state), counts.tiles, record.maps_received,
               record.bytes_received + counts.bytes, record.rejected_samples + counts.rejected,
               record.id_clashes, placement);
  }
  fmt::print(
      "fused map: {} tiles; published {} fused tile revisions ({} bytes) and {} grids on "
      "{}; {} samples rejected before they named a robot\n",
      fusion.fused_tiles, fusion.fused_tiles_published, fusion.fused_bytes_published,
      fusion.maps_published,
      options_.shard ? transport::ShardMapTopic(options_.shard->name) : transport::kFleetMapTopic,
      fusion.rejected_unattributed);
  if (options_.shard) {
    fmt::print(
        "shard {}: {} robot tiles on no shard's region (not fused anywhere), {} tiles of other "
        "shards received (from writers that do not filter)\n",
        options_.shard->name, fusion.tiles_on_no_shard, fusion.tiles_of_other_shards);
  }
  if (fusion.quarantines > 0 || !fusion.standings.empty()) {
    std::string now;
    for (const auto& [robot, report] : fusion.standings) {
      if (report.standing == fusion::Standing::kTrusted) continue;
      now += fmt::format("{}{} {}", now.empty() ? "" : ", ", robot.value,
                         fusion::StandingName(report.standing));
    }
    fmt::print("quarantine: {} robots entered it; now {}\n", fusion.quarantines,
               now.empty() ? "none quarantined or admitted" : now);
  }
  if (!fusion.refusals_by_reason.empty() || refusals_.total() > 0) {
    std::string reasons;
    for (const auto& [reason, count] : fusion.refusals_by_reason) {
      reasons += fmt::format("{}{} {}", reasons.empty() ? "" : ", ", count, reason);
    }
    std::map<std::string, uint64_t> others;
    for (const auto& [robot, counts] : refusals_.counts()) {
      for (const auto& [reason, count] : counts) others[RefusalName(reason)] += count;
    }
    std::string other_reasons;
    for (const auto& [reason, count] : others) {
      other_reasons += fmt::format(", {} {}", count, reason);
    }
    fmt::print("refused: tiles: {}; statuses, disposals, entities and map samples: {}{}\n",
               reasons.empty() ? "none" : reasons, refusals_.total(), other_reasons);
  }
  if (learning_worker_) {
    const ObjectLearningStats learning = learning_worker_->stats();
    fmt::print(
        "object learning: {} sessions finished; {} runs ({} failed, {} degraded by the memory "
        "budget); last: {} objects of {} templates from {} sessions{}\n",
        fusion.sessions_finished, learning.runs, learning.failures, learning.degraded_runs,
        learning.num_objects, learning.num_templates, learning.sessions_used,
        learning.progress.stage == object_learning::LearnStage::kDone
            ? std::string()
            : "; now " + object_learning::DescribeProgress(learning.progress));
  }
  if (prediction_worker_) {
    const PredictionStats prediction = prediction_worker_->stats();
    const extrapolation::TrackerStats& tracker = prediction.tracker;
    fmt::print(
        "extrapolation: {} entities ({} rejected), {} places, {} predicted sub-maps ({} "
        "confirmed, {} retracted), {} sub-map samples published\n",
        tracker.entities, rejected_entities_, tracker.places, tracker.predictions,
        tracker.confirmed, tracker.retracted, prediction.submaps_published);
  }
  if (route_graph_worker_) {
    const RouteGraphStats graph = route_graph_worker_->stats();
    fmt::print(
        "route graph: revision {}, {} nodes, {} edges ({} through predicted space, {} blocked by "
        "learned objects), {} rooms; {} builds, {} updates\n",
        graph.revision, graph.nodes, graph.edges, graph.predicted_edges, graph.blocked_edges,
        graph.rooms, graph.builds, graph.updates);
  }
  // Queues that were full dropped their oldest entries: a worker fell behind its inputs.
  fmt::print(
      "dropped from full queues: {} tile events, {} grids, {} robot records (fusion); {} "
      "entities, {} inputs (extrapolation)\n",
      fusion.tile_events_dropped, fusion.grids_dropped, fusion.robot_records_dropped,
      entity_reader_ ? entity_reader_->dropped() : 0,
      prediction_worker_ ? prediction_worker_->stats().inputs_dropped : 0);
  std::fflush(stdout);
}

void ServerOptions::Describe(OptionsPrinter& out) const {
  out.Add("duration", duration);
  out.Nested("dds", dds);
  out.Nested("map", map);
  out.Nested("worker", worker);
  out.Nested("learning", learning);
  out.Nested("prediction", prediction);
  out.Nested("route_graph", route_graph);
  out.Add("transforms", transforms);
  out.Add("max_robots_per_participant", max_robots_per_participant);
  out.Add("name", name);
  out.Add("ownership_strength", ownership_strength);
  if (shard) out.Add("shard", shard->name);
}

}  // namespace fleetmap::server
