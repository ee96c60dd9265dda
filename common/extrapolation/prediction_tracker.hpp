#pragma once

// The fleet's prediction lifecycle (docs/extrapolation.md, docs/fleet.md "Predicted space"), with
// no DDS in it: what the server's prediction worker thinks, while the worker only queues inputs,
// runs the tracker on its thread and writes what changed on rt/fleetmap/submap_graph.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/extrapolation/extrapolator.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/scene/entities.hpp"
#include "common/scene/submap_graph.hpp"
#include "common/scene/submap_node.hpp"

namespace fleetmap::extrapolation {

// Predicted sub-maps are numbered from here; observed places from 0.
inline constexpr uint32_t kFirstPredictedSubmap = 1u << 20;
// The value of a cell of an observed place that only people's tracks make free.
inline constexpr int8_t kConditionallyFree = 1;

struct PredictionOptions {
  // Whether the server predicts at all (--no-extrapolation); the tracker ignores it.
  bool enabled = true;
  ExtrapolationOptions extrapolation;
  // A prediction is judged once robots have observed this share of what it added to the map
  // (and at least `min_observed_cells` cells): confirmed when at least `confirm_precision` of
  // the observed cells are free, retracted otherwise.
  double judge_observed_fraction = 0.5;
  int64_t min_observed_cells = 20;
  double confirm_precision = 0.9;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// An entity a robot recognises, or a new version of it, in the fleet frame.
struct RobotEntity {
  RobotId robot;
  Timestamp stamp{};
  scene::Entity entity;
};

// The robot no longer reports the entity.
struct EntityRemoval {
  RobotId robot;
  std::string entity_id;
};

// What the tracker takes, in arrival order: entities, their removals, and fused grids (fleet
// frame; only the newest of a batch counts).
using TrackerInput = std::variant<RobotEntity, EntityRemoval, grid::OccupancyGrid>;

// A sub-map node to publish (kWrite) or withdraw (kWithdraw: only `node.submap.id` is set).
struct SubmapChange {
  enum class Kind { kWrite, kWithdraw };
  Kind kind = Kind::kWrite;
  scene::SubmapNode node;
};

// A line for the caller's log.
struct TrackerNote {
  enum class Level { kInfo, kWarning };
  Level level = Level::kInfo;
  std::string text;
};

// What one batch changed: the sub-maps to write or withdraw, in order, and what to log.
struct TrackerUpdate {
  std::vector<SubmapChange> changes;
  std::vector<TrackerNote> notes;
};

struct TrackerStats {
  uint64_t entities = 0;  // known now
  uint64_t places = 0;    // observed places of the fused map
  uint64_t predictions = 0;
  uint64_t confirmed = 0;
  uint64_t retracted = 0;
};

// Keeps the fleet's sub-map graph from the entities robots recognise (doors, stairs, people; in
// the fleet frame) and the fused grid: a sub-map predicted behind each closed door and at the top
// of each flight of stairs, and conditionally free space along people's tracks. The fused map is
// split into topological places at doors and stairs: sub-maps 0..K-1, one per place, carrying the
// place's free cells (kConditionallyFree where only people's tracks make them free) and edges
// through the doors between them. Each prediction (ids from kFirstPredictedSubmap, stable per
// robot and entity across re-predictions) is a node joined to the place its door or stairs opens
// from.
//
// A prediction is made once per entity (again only when the entity changes: an identical re-sent
// entity, scene::SameEntity, changes nothing) against the fused map of that moment, and withdrawn
// when the entity no longer predicts anything (the door opened) or is removed. It is then checked
// against every later fused map, counting only the cells it added (unknown when it was made); once
// robots have observed enough of it, it is confirmed or retracted, with its measured precision. A
// prediction for another floor (up the stairs) stays predicted. Places are published only when
// they change; none while no entity is known.
//
// Not thread-safe: one thread (the prediction worker's) calls everything.
class PredictionTracker {
 public:
  // Fails when the options are invalid.
  static StatusOr<PredictionTracker> Create(const PredictionOptions& options);

  // Takes one batch of inputs, in arrival order, and returns what changed. Predictions wait for
  // the first fused grid. `now` stamps the nodes written.
  TrackerUpdate Handle(std::vector<TrackerInput> inputs, Timestamp now);

  TrackerStats stats() const { return stats_; }
  // The door robot `robot` reported as `entity_id` (fleet frame), if it did and it is a door:
  // where a sub-map predicted behind it is entered.
  std::optional<scene::DoorEntity> Door(const RobotId& robot, const std::string& entity_id) const;

 private:
  struct Prediction {
    scene::SubmapNode node;
    // What the prediction added: its free cells that were unknown when it was made.
    scene::Submap added;
    bool judged = false;
  };

  explicit PredictionTracker(const PredictionOptions& options) : options_(options) {}

  // Predicts behind one door or up one flight of stairs; withdraws the old prediction if the
  // entity no longer gives one (an open door).
  void Predict(const std::string& key, const RobotEntity& entity, Timestamp now,
               TrackerUpdate* update);
  void Withdraw(const std::string& key, TrackerUpdate* update);
  // Splits the fused map into places (with every door and stairs) and marks the conditionally
  // free cells of people's tracks; publishes the places that changed.
  void UpdatePlaces(Timestamp now, TrackerUpdate* update);
  void CheckPredictions(Timestamp now, TrackerUpdate* update);
  // The observed places with their edges: between places, and to the predictions.
  void PublishPlaces(Timestamp now, TrackerUpdate* update);

  PredictionOptions options_;
  std::optional<grid::OccupancyGrid> map_;
  std::map<std::string, RobotEntity> entities_;    // by "robot/entity"
  std::map<std::string, Prediction> predictions_;  // by "robot/entity"
  std::vector<std::string> unpredicted_;           // doors and stairs waiting for a map
  scene::SubmapGraph places_;                      // observed places and their edges, fleet frame
  std::map<std::string, uint32_t> place_of_;       // the place each door or stairs opens from
  std::vector<scene::SubmapNode> published_places_;
  uint32_t next_submap_id_ = kFirstPredictedSubmap;
  std::map<std::string, uint32_t> submap_ids_;  // stable per entity across re-predictions
  TrackerStats stats_;
};

}  // namespace fleetmap::extrapolation
