#include "server/prediction_worker.hpp"

#include <spdlog/spdlog.h>

#include <utility>

namespace fleetmap::server {

StatusOr<std::unique_ptr<PredictionWorker>> PredictionWorker::Create(
    transport::Participant& participant, const extrapolation::PredictionOptions& options,
    PublishedIds ids) {
  StatusOr<extrapolation::PredictionTracker> tracker =
      extrapolation::PredictionTracker::Create(options);
  if (!tracker.ok()) return tracker.status().WithContext("map extrapolation");
  std::unique_ptr<PredictionWorker> worker(new PredictionWorker(std::move(tracker).value()));
  worker->ids_ = std::move(ids);
  FLEETMAP_ASSIGN_OR_RETURN(worker->writer_, transport::SubmapWriter::Create(participant));
  return worker;
}

PredictionWorker::~PredictionWorker() {
  Stop();
  writer_.reset();
}

void PredictionWorker::Start() {
  thread_.Start([this] {
    HandleInputs();
    return false;
  });
}

void PredictionWorker::Stop() { thread_.Stop(); }

void PredictionWorker::Submit(extrapolation::TrackerInput input) {
  inputs_.Push(std::move(input));
  thread_.Wake();
}

void PredictionWorker::SubmitEntity(transport::EntityMessage entity) {
  Submit(
      extrapolation::RobotEntity{std::move(entity.robot), entity.stamp, std::move(entity.entity)});
}

void PredictionWorker::RemoveEntity(const RobotId& robot, const std::string& entity_id) {
  Submit(extrapolation::EntityRemoval{robot, entity_id});
}

void PredictionWorker::SubmitMap(grid::OccupancyGrid map) { Submit(std::move(map)); }

PredictionStats PredictionWorker::stats() const {
  PredictionStats stats;
  stats.inputs_dropped = inputs_.dropped();
  std::lock_guard lock(stats_mutex_);
  stats.tracker = tracker_stats_;
  stats.submaps_published = submaps_published_;
  return stats;
}

void PredictionWorker::HandleInputs() {
  std::vector<extrapolation::TrackerInput> inputs = inputs_.Drain();
  if (inputs.empty()) return;
  const extrapolation::TrackerUpdate update = tracker_.Handle(std::move(inputs), Clock::now());
  for (const extrapolation::TrackerNote& note : update.notes) {
    if (note.level == extrapolation::TrackerNote::Level::kWarning) {
      spdlog::warn("server: {}", note.text);
    } else {
      spdlog::info("server: {}", note.text);
    }
  }
  for (const extrapolation::SubmapChange& change : update.changes) Apply(change);
  std::lock_guard lock(stats_mutex_);
  tracker_stats_ = tracker_.stats();
}

void PredictionWorker::Apply(const extrapolation::SubmapChange& change) {
  if (listener_) {
    const std::optional<scene::DoorEntity> door =
        tracker_.Door(change.node.source_robot, change.node.source_entity);
    listener_(change.node, door ? &*door : nullptr,
              change.kind == extrapolation::SubmapChange::Kind::kWithdraw);
  }
  scene::SubmapNode node = change.node;
  node.submap.id = ids_(node.submap.id);
  for (scene::SubmapEdge& edge : node.edges) {
    edge.from = ids_(edge.from);
    edge.to = ids_(edge.to);
  }
  if (change.kind == extrapolation::SubmapChange::Kind::kWithdraw) {
    if (Status disposed = writer_->Dispose(node); !disposed.ok()) {
      spdlog::warn("server: {}", disposed.message());
    }
    return;
  }
  StatusOr<size_t> written = writer_->Write(node);
  if (!written.ok()) {
    spdlog::warn("server: sub-map {}: {}", node.submap.id, written.status().message());
    return;
  }
  std::lock_guard lock(stats_mutex_);
  ++submaps_published_;
}

}  // namespace fleetmap::server
