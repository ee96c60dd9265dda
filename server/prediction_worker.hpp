#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/core/sample_queue.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/extrapolation/prediction_tracker.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "server/published_ids.hpp"

namespace fleetmap::server {

// What the predictions have done. A snapshot; thread-safe to take.
struct PredictionStats {
  extrapolation::TrackerStats tracker;
  uint64_t submaps_published = 0;
  uint64_t inputs_dropped = 0;  // entities, removals and grids dropped from the full input queue
};

// The server's map extrapolation on its own thread: entities (already in the fleet frame), their
// removals and the fused grids queue here; the worker hands each batch to an
// extrapolation::PredictionTracker (the lifecycle: places, predictions, confirm / retract) and
// writes the sub-maps that changed on rt/fleetmap/submap_graph, disposing those it withdrew.
//
// SubmitEntity(), RemoveEntity(), SubmitMap() and stats() may be called from any thread; Start()
// and Stop() from the owner's. Stop() lets the batch in progress finish; what is queued after it
// is not handled.
class PredictionWorker {
 public:
  static StatusOr<std::unique_ptr<PredictionWorker>> Create(
      transport::Participant& participant, const extrapolation::PredictionOptions& options,
      PublishedIds ids = {});
  ~PredictionWorker();

  // Told each sub-map the worker wrote (`withdrawn` false) or withdrew, on the worker's thread,
  // with the tracker's ids, and for a prediction behind a door the door (else null): e.g. the
  // route graph's rooms and predicted space. Set before Start().
  using SubmapListener = std::function<void(const scene::SubmapNode& node,
                                            const scene::DoorEntity* door, bool withdrawn)>;
  void SetListener(SubmapListener listener) { listener_ = std::move(listener); }

  void Start();
  void Stop();

  // An entity, or a new version of it, in the fleet frame.
  void SubmitEntity(transport::EntityMessage entity);
  void RemoveEntity(const RobotId& robot, const std::string& entity_id);
  // The newest fused grid (fleet frame).
  void SubmitMap(grid::OccupancyGrid map);
  PredictionStats stats() const;

 private:
  explicit PredictionWorker(extrapolation::PredictionTracker tracker)
      : tracker_(std::move(tracker)) {}

  void Submit(extrapolation::TrackerInput input);
  // One round of the worker: the queued inputs through the tracker, its changes on the wire.
  void HandleInputs();
  void Apply(const extrapolation::SubmapChange& change);

  extrapolation::PredictionTracker tracker_;  // worker thread only
  PublishedIds ids_;                          // the sub-map ids it writes
  std::unique_ptr<transport::SubmapWriter> writer_;
  SubmapListener listener_;
  SampleQueue<extrapolation::TrackerInput> inputs_{4096};

  mutable std::mutex stats_mutex_;
  uint64_t submaps_published_ = 0;             // guarded by stats_mutex_
  extrapolation::TrackerStats tracker_stats_;  // guarded by stats_mutex_
  // Wakes on every input, and at least every 100 ms. Last member: its thread stops first.
  WorkerThread thread_{std::chrono::milliseconds(100)};
};

}  // namespace fleetmap::server
