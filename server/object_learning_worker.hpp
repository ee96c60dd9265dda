#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/fusion/fusion_options.hpp"
#include "common/object_learning/object_learner.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "server/published_ids.hpp"
#include "server/session_archive.hpp"

namespace fleetmap::server {

struct ObjectLearningOptions {
  bool enabled = true;
  // Learning starts once this many sessions have finished; it uses the newest `max_sessions`.
  size_t min_sessions = 2;
  size_t max_sessions = 12;
  // The server's own memory budget for one learning run (it replaces learn.memory_budget_mb):
  // the learner degrades past it (fewer sessions, coarser patches) rather than take the server's
  // memory with it. 12 sessions of an 80 x 60 m building at 5 cm are 23 MB of grids.
  double memory_budget_mb = 512.0;
  // How often a learning run in progress is logged (its stage, (N, M), elapsed, estimate).
  double progress_log_seconds = 30.0;
  object_learning::LearnOptions learn;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// What the learner has done. A snapshot; thread-safe to take.
struct ObjectLearningStats {
  uint64_t runs = 0;
  uint64_t failures = 0;
  int num_objects = 0;  // of the last successful run
  int num_templates = 0;
  size_t sessions_used = 0;
  uint64_t degraded_runs = 0;  // runs the memory budget made degrade
  // The run in progress (stage kDone when none): its last progress report.
  object_learning::LearnProgress progress{object_learning::LearnStage::kDone};
};

// Runs the object-template learner (hierarchical EM over the differences between mapping
// sessions, docs/object-learning.md) in the background whenever a session finishes, and
// publishes the learned templates on rt/fleetmap/object_templates and objects on
// rt/fleetmap/objects, replacing the previous run's (instances the new run no longer has are
// disposed). Learning takes seconds: a newer submission replaces one that has not started yet
// (one slot, not a queue: nothing is dropped that a newer submission does not supersede), and
// Stop() cancels a run in progress; a submission still waiting then is not learned.
// Submit() and stats() from any thread; Start() and Stop() from the owner's.
class ObjectLearningWorker {
 public:
  static StatusOr<std::unique_ptr<ObjectLearningWorker>> Create(
      transport::Participant& participant, const ObjectLearningOptions& options,
      const fusion::FusionOptions& fusion, PublishedIds ids = {});
  ~ObjectLearningWorker();

  // Told the objects of each learning run once they are on the wire (ids as published), on the
  // worker's thread (e.g. the route graph marks the edges they block). Set before Start().
  using ObjectsListener = std::function<void(const std::vector<transport::ObjectModelMessage>&)>;
  void SetListener(ObjectsListener listener) { listener_ = std::move(listener); }

  void Start();
  void Stop();

  // The finished sessions to learn from (all of them; the worker keeps the newest).
  void Submit(std::vector<MappingSession> sessions);
  ObjectLearningStats stats() const;

 private:
  ObjectLearningWorker(const ObjectLearningOptions& options, const fusion::FusionOptions& fusion)
      : options_(options), fusion_(fusion) {}

  // One round of the worker: learns from the pending submission, if any.
  void LearnPending();
  Status Learn(const std::vector<MappingSession>& sessions);
  Status Publish(const object_learning::LearnedModel& model,
                 const std::vector<MappingSession>& sessions);

  const ObjectLearningOptions options_;
  const fusion::FusionOptions fusion_;
  std::unique_ptr<transport::ObjectTemplateWriter> template_writer_;  // worker thread
  std::unique_ptr<transport::ObjectModelWriter> object_writer_;       // worker thread
  PublishedIds ids_;  // the template and object ids it writes
  ObjectsListener listener_;
  uint32_t learning_run_ = 0;         // worker thread
  uint32_t published_templates_ = 0;  // worker thread
  uint32_t published_objects_ = 0;    // worker thread

  mutable std::mutex mutex_;
  std::optional<std::vector<MappingSession>> pending_;  // guarded by mutex_
  std::atomic<bool> cancel_{false};                     // stops a learning run in progress (Stop())
  ObjectLearningStats stats_;                           // guarded by mutex_
  // Wakes on Submit() only (no timeout). Last member: its thread stops first.
  WorkerThread thread_{std::nullopt};
};

}  // namespace fleetmap::server
