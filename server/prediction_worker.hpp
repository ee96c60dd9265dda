#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/core/status.hpp"
#include "common/extrapolation/extrapolator.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/wake_up.hpp"

namespace fleetmap::server {

// Predicted sub-maps are numbered from here; observed places from 0.
inline constexpr uint32_t kFirstPredictedSubmap = 1u << 20;
// The value of a cell of an observed place that only people's tracks make free.
inline constexpr int8_t kConditionallyFree = 1;

struct PredictionOptions {
  bool enabled = true;
  extrapolation::ExtrapolationOptions extrapolation;
  // A prediction is judged once robots have observed this share of what it added to the map
  // (and at least `min_observed_cells` cells): confirmed when at least `confirm_precision` of
  // the observed cells are free, retracted otherwise.
  double judge_observed_fraction = 0.5;
  int64_t min_observed_cells = 20;
  double confirm_precision = 0.9;

  Status Validate() const;
};

// What the predictions have done. A snapshot; thread-safe to take.
struct PredictionStats {
  uint64_t entities = 0;  // known now
  uint64_t places = 0;    // observed places of the fused map
  uint64_t predictions = 0;
  uint64_t confirmed = 0;
  uint64_t retracted = 0;
  uint64_t submaps_published = 0;
};

// The server's map extrapolation (docs/extrapolation.md): from the entities the robots recognise
// (doors, stairs, people; already in the fleet frame) and the fused grid, predicts sub-maps behind
// closed doors and at the top of stairs, and the conditionally free space along people's tracks,
// and publishes the sub-map graph on rt/fleetmap/submap_graph. The observed fleet map is split
// into topological places at doors and stairs: sub-maps 0..K-1, one per place, carrying the
// place's free cells (kConditionallyFree where only people's tracks make them free) and edges
// through the doors between them. Each prediction (ids from kFirstPredictedSubmap) is a node
// joined to the place its door or stairs opens from.
//
// A prediction is made once per entity (again only when the entity changes) against the fused
// map of that moment, and then checked against every later fused map: only the cells it added
// (unknown when it was made) count. Once robots have observed enough of it, it is confirmed or
// retracted and its measured precision is published with it.
//
// Everything runs on the worker's thread. SubmitEntity(), RemoveEntity(), SubmitMap() and
// stats() may be called from any thread; Start() and Stop() from the owner's.
class PredictionWorker {
 public:
  static StatusOr<std::unique_ptr<PredictionWorker>> Create(transport::Participant& participant,
                                                            const PredictionOptions& options);
  ~PredictionWorker();

  void Start();
  void Stop();

  // An entity, or a new version of it, in the fleet frame.
  void SubmitEntity(transport::EntityMessage entity);
  void RemoveEntity(const RobotId& robot, const std::string& entity_id);
  // The newest fused grid (fleet frame).
  void SubmitMap(grid::OccupancyGrid map);
  PredictionStats stats() const;

 private:
  struct Input {
    enum class Kind { kEntity, kRemoved, kMap };
    Kind kind = Kind::kEntity;
    transport::EntityMessage entity;  // kEntity; robot and id for kRemoved
    grid::OccupancyGrid map;          // kMap
  };
  struct Prediction {
    transport::SubmapMessage message;
    // What the prediction added: its free cells that were unknown when it was made.
    scene::Submap added;
    bool judged = false;
  };

  PredictionWorker(const PredictionOptions& options) : options_(options) {}

  void Loop();
  void HandleInputs();
  // Predicts behind one door or up one flight of stairs; withdraws the old prediction if the
  // entity no longer gives one (an open door).
  void Predict(const std::string& key, const transport::EntityMessage& entity);
  void Withdraw(const std::string& key);
  // Splits the fused map into places (with every door and stairs) and marks the conditionally
  // free cells of people's tracks; publishes the places that changed.
  void UpdatePlaces();
  void CheckPredictions();
  // The observed places with their edges: between places, and to the predictions.
  void PublishPlaces();
  void Publish(const transport::SubmapMessage& message);

  const PredictionOptions options_;
  std::unique_ptr<transport::SubmapWriter> writer_;
  std::shared_ptr<transport::WakeUp> wake_up_ = std::make_shared<transport::WakeUp>();
  transport::SampleQueue<Input> inputs_{4096};

  // Worker thread only.
  std::optional<grid::OccupancyGrid> map_;
  std::map<std::string, transport::EntityMessage> entities_;  // by "robot/entity"
  std::map<std::string, Prediction> predictions_;             // by "robot/entity"
  std::vector<std::string> unpredicted_;                      // doors and stairs waiting for a map
  scene::SubmapGraph places_;                 // observed places and their edges, fleet frame
  std::map<std::string, uint32_t> place_of_;  // the place each door or stairs opens from
  std::vector<transport::SubmapMessage> published_places_;
  uint32_t next_submap_id_ = kFirstPredictedSubmap;
  std::map<std::string, uint32_t> submap_ids_;  // stable per entity across re-predictions

  std::atomic<bool> stop_{false};
  std::thread thread_;
  mutable std::mutex stats_mutex_;
  PredictionStats stats_;  // guarded by stats_mutex_
};

}  // namespace fleetmap::server
