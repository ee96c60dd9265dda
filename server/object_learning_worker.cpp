#include "server/object_learning_worker.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "server/session_grids.hpp"

namespace fleetmap::server {

Status ObjectLearningOptions::Validate() const {
  if (min_sessions < 2) {
    return InvalidArgumentError("learning needs at least 2 sessions (min_sessions " +
                                std::to_string(min_sessions) + ")");
  }
  if (max_sessions < min_sessions) {
    return InvalidArgumentError("max_sessions " + std::to_string(max_sessions) +
                                " is below min_sessions " + std::to_string(min_sessions));
  }
  if (!(memory_budget_mb > 0.0)) {
    return InvalidArgumentError("memory_budget_mb " + std::to_string(memory_budget_mb) +
                                " must be > 0");
  }
  return learn.Validate();
}

StatusOr<std::unique_ptr<ObjectLearningWorker>> ObjectLearningWorker::Create(
    transport::Participant& participant, const ObjectLearningOptions& options,
    const fusion::FusionOptions& fusion, PublishedIds ids) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate().WithContext("object learning"));
  std::unique_ptr<ObjectLearningWorker> worker(new ObjectLearningWorker(options, fusion));
  worker->ids_ = std::move(ids);
  FLEETMAP_ASSIGN_OR_RETURN(worker->template_writer_,
                            transport::ObjectTemplateWriter::Create(participant));
  FLEETMAP_ASSIGN_OR_RETURN(worker->object_writer_,
                            transport::ObjectModelWriter::Create(participant));
  return worker;
}

ObjectLearningWorker::~ObjectLearningWorker() {
  Stop();
  template_writer_.reset();
  object_writer_.reset();
}

void ObjectLearningWorker::Start() {
  thread_.Start([this] {
    LearnPending();
    return false;
  });
}

void ObjectLearningWorker::Stop() {
  cancel_.store(true);  // first: a run in progress ends, and no other starts
  thread_.Stop();
}

void ObjectLearningWorker::Submit(std::vector<MappingSession> sessions) {
  if (sessions.size() < options_.min_sessions) return;
  if (sessions.size() > options_.max_sessions) {
    sessions.erase(sessions.begin(),
                   sessions.end() - static_cast<std::ptrdiff_t>(options_.max_sessions));
  }
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(sessions);
  }
  thread_.Wake();
}

ObjectLearningStats ObjectLearningWorker::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void ObjectLearningWorker::LearnPending() {
  std::vector<MappingSession> sessions;
  {
    std::lock_guard lock(mutex_);
    if (cancel_.load() || !pending_.has_value()) return;  // stopping, or woken for nothing
    sessions = std::move(*pending_);
    pending_.reset();
  }
  const Status learned = Learn(sessions);
  if (cancel_.load()) return;  // stopping: the cancelled run is not a failure
  std::lock_guard lock(mutex_);
  if (!learned.ok()) {
    ++stats_.failures;
    spdlog::warn("server: object learning: {}", learned.message());
  }
}

Status ObjectLearningWorker::Learn(const std::vector<MappingSession>& sessions) {
  // The sessions' grids (a byte a cell) take at most a quarter of the learner's memory budget;
  // its memory plan sizes the EM's working set from the rest. Without this bound, a dozen
  // sessions spread wide (a peer's ids, tiles far apart) made a dozen of the largest grids.
  const double grid_bytes = options_.memory_budget_mb * double{1 << 20} / 4.0;
  const auto max_cells =
      static_cast<int64_t>(grid_bytes / static_cast<double>(std::max<size_t>(1, sessions.size())));
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<grid::OccupancyGrid> grids,
                            SessionGrids(sessions, fusion_, max_cells));
  object_learning::LearnOptions learn = options_.learn;
  learn.cancel = &cancel_;
  learn.memory_budget_mb = options_.memory_budget_mb;
  // Progress: kept for the status counters on every report, logged at a low rate.
  auto last_log = std::chrono::steady_clock::now();
  learn.progress = [this, &last_log](const object_learning::LearnProgress& p) {
    {
      std::lock_guard lock(mutex_);
      stats_.progress = p;
    }
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_log).count() >= options_.progress_log_seconds) {
      last_log = now;
      spdlog::info("server: object learning: {}", object_learning::DescribeProgress(p));
    }
  };
  StatusOr<object_learning::LearnedModel> learned = object_learning::LearnObjects(grids, learn);
  {
    std::lock_guard lock(mutex_);
    stats_.progress.stage = object_learning::LearnStage::kDone;
  }
  FLEETMAP_ASSIGN_OR_RETURN(const object_learning::LearnedModel model, std::move(learned));
  for (const std::string& warning : model.warnings) {
    spdlog::info("server: object learning: {}", warning);
  }
  FLEETMAP_RETURN_IF_ERROR(Publish(model, sessions));
  spdlog::info("server: learned {} objects of {} templates from {} sessions (run {})",
               model.num_objects, model.num_templates, sessions.size(), learning_run_);
  std::lock_guard lock(mutex_);
  ++stats_.runs;
  stats_.num_objects = model.num_objects;
  stats_.num_templates = model.num_templates;
  stats_.sessions_used = sessions.size();
  if (model.degraded) ++stats_.degraded_runs;
  return Status::Ok();
}

Status ObjectLearningWorker::Publish(const object_learning::LearnedModel& model,
                                     const std::vector<MappingSession>& sessions) {
  ++learning_run_;
  const Timestamp now = Clock::now();
  std::vector<uint32_t> object_count(model.templates.size(), 0);
  for (const int z : model.object_template) {
    if (z >= 0 && static_cast<size_t>(z) < object_count.size()) ++object_count[z];
  }
  for (size_t m = 0; m < model.templates.size(); ++m) {
    transport::ObjectTemplateMessage message;
    message.template_id = ids_(static_cast<uint32_t>(m));
    message.learning_run = learning_run_;
    message.object_count = object_count[m];
    message.patch = model.templates[m];
    message.stamp = now;
    FLEETMAP_RETURN_IF_ERROR(template_writer_->Write(message).status());
  }
  std::vector<transport::ObjectModelMessage> objects;
  for (size_t n = 0; n < model.objects.size(); ++n) {
    transport::ObjectModelMessage message;
    message.object_id = ids_(static_cast<uint32_t>(n));
    message.learning_run = learning_run_;
    message.template_id = ids_(n < model.object_template.size()
                                   ? static_cast<uint32_t>(std::max(0, model.object_template[n]))
                                   : 0);
    message.patch = model.objects[n];
    message.stamp = now;
    for (const object_learning::SnapshotAssignment& snapshot : model.snapshots) {
      if (snapshot.object != static_cast<int>(n)) continue;
      transport::ObjectSighting sighting;
      sighting.session = static_cast<uint32_t>(sessions.at(snapshot.map_index).id);
      sighting.fleet_from_object = object_learning::ObjectPoseInMap(snapshot);  // fleet = map
      message.sightings.push_back(sighting);
    }
    FLEETMAP_RETURN_IF_ERROR(object_writer_->Write(message).status());
    objects.push_back(std::move(message));
  }
  // What the previous run had and this one has not.
  for (uint32_t m = static_cast<uint32_t>(model.templates.size()); m < published_templates_; ++m) {
    transport::ObjectTemplateMessage key;
    key.template_id = ids_(m);
    FLEETMAP_RETURN_IF_ERROR(template_writer_->Dispose(key));
  }
  for (uint32_t n = static_cast<uint32_t>(model.objects.size()); n < published_objects_; ++n) {
    transport::ObjectModelMessage key;
    key.object_id = ids_(n);
    FLEETMAP_RETURN_IF_ERROR(object_writer_->Dispose(key));
  }
  published_templates_ = static_cast<uint32_t>(model.templates.size());
  published_objects_ = static_cast<uint32_t>(model.objects.size());
  if (listener_) listener_(objects);
  return Status::Ok();
}

void ObjectLearningOptions::Describe(OptionsPrinter& out) const {
  out.Add("enabled", enabled);
  out.Add("min_sessions", min_sessions);
  out.Add("max_sessions", max_sessions);
  out.Add("memory_budget_mb", memory_budget_mb);
  out.Add("progress_log_seconds", progress_log_seconds);
  out.Nested("learn", learn);
}

}  // namespace fleetmap::server
