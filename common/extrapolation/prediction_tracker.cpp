#include "common/extrapolation/prediction_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <utility>

#include "common/extrapolation/prediction_check.hpp"
#include "common/scene/entity_frames.hpp"

namespace fleetmap::extrapolation {
namespace {

std::string KeyOf(const RobotId& robot, const std::string& entity_id) {
  return robot.value + "/" + entity_id;
}

bool PredictsASubmap(const scene::Entity& entity) {
  return !std::holds_alternative<scene::PersonTrack>(entity);
}

// Adds the entity to `entities` under the id `id`.
void AddTo(scene::Entity entity, const std::string& id, scene::Entities* entities) {
  std::visit(
      [entities, &id](auto& one) {
        one.id = id;
        using T = std::decay_t<decltype(one)>;
        if constexpr (std::is_same_v<T, scene::DoorEntity>) {
          entities->doors.push_back(std::move(one));
        } else if constexpr (std::is_same_v<T, scene::StairsEntity>) {
          entities->stairs.push_back(std::move(one));
        } else {
          entities->people.push_back(std::move(one));
        }
      },
      entity);
}

// The sub-map with only the free cells that `known` did not already show free or occupied.
scene::Submap AddedCells(const scene::Submap& submap, const grid::OccupancyGrid& known) {
  scene::Submap added = submap;
  const Transform2 map_from_submap = submap.map_from_submap.ToTransform();
  grid::OccupancyGrid& cells = added.navigable;
  for (int y = 0; y < cells.height(); ++y) {
    for (int x = 0; x < cells.width(); ++x) {
      if (cells.StateAt(x, y) != grid::CellState::kFree) continue;
      const auto index = known.CellAt(map_from_submap * cells.CellCenter(x, y));
      if (index && known.StateAt(index->x, index->y) != grid::CellState::kUnknown) {
        cells.at(x, y) = grid::kUnknownValue;
      }
    }
  }
  return added;
}

void Note(TrackerNote::Level level, std::string text, TrackerUpdate* update) {
  update->notes.push_back({level, std::move(text)});
}

void Write(const scene::SubmapNode& node, TrackerUpdate* update) {
  update->changes.push_back({SubmapChange::Kind::kWrite, node});
}

void Withdrawal(uint32_t id, TrackerUpdate* update) {
  SubmapChange change;
  change.kind = SubmapChange::Kind::kWithdraw;
  change.node.submap.id = id;
  update->changes.push_back(std::move(change));
}

}  // namespace

Status PredictionOptions::Validate() const {
  if (!(judge_observed_fraction > 0.0 && judge_observed_fraction <= 1.0)) {
    return InvalidArgumentError("judge_observed_fraction " +
                                std::to_string(judge_observed_fraction) + " must be in (0, 1]");
  }
  if (!(confirm_precision >= 0.0 && confirm_precision <= 1.0)) {
    return InvalidArgumentError("confirm_precision " + std::to_string(confirm_precision) +
                                " must be in [0, 1]");
  }
  if (min_observed_cells < 1) {
    return InvalidArgumentError("min_observed_cells " + std::to_string(min_observed_cells) +
                                " must be at least 1");
  }
  return extrapolation.Validate();
}

StatusOr<PredictionTracker> PredictionTracker::Create(const PredictionOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  return PredictionTracker(options);
}

std::optional<scene::DoorEntity> PredictionTracker::Door(const RobotId& robot,
                                                         const std::string& entity_id) const {
  const auto found = entities_.find(KeyOf(robot, entity_id));
  if (found == entities_.end()) return std::nullopt;
  const auto* door = std::get_if<scene::DoorEntity>(&found->second.entity);
  if (door == nullptr) return std::nullopt;
  return *door;
}

TrackerUpdate PredictionTracker::Handle(std::vector<TrackerInput> inputs, Timestamp now) {
  TrackerUpdate update;
  if (inputs.empty()) return update;
  bool map_changed = false;
  bool people_changed = false;
  bool removed = false;
  // Only the newest map matters; entities in arrival order.
  for (TrackerInput& input : inputs) {
    if (auto* map = std::get_if<grid::OccupancyGrid>(&input)) {
      map_ = std::move(*map);
      map_changed = true;
      continue;
    }
    if (const auto* removal = std::get_if<EntityRemoval>(&input)) {
      const std::string key = KeyOf(removal->robot, removal->entity_id);
      const auto it = entities_.find(key);
      if (it == entities_.end()) continue;
      removed = true;
      entities_.erase(it);
      std::erase(unpredicted_, key);
      Withdraw(key, &update);
      continue;
    }
    RobotEntity& entity = std::get<RobotEntity>(input);
    const std::string key = KeyOf(entity.robot, scene::EntityId(entity.entity));
    const auto it = entities_.find(key);
    if (it != entities_.end() && scene::SameEntity(it->second.entity, entity.entity)) continue;
    if (it != entities_.end() &&
        PredictsASubmap(it->second.entity) != PredictsASubmap(entity.entity)) {
      Withdraw(key, &update);  // an id reused for another kind of entity
      people_changed = true;
    }
    people_changed |= !PredictsASubmap(entity.entity);
    if (PredictsASubmap(entity.entity) &&
        std::find(unpredicted_.begin(), unpredicted_.end(), key) == unpredicted_.end()) {
      unpredicted_.push_back(key);
    }
    entities_[key] = std::move(entity);
  }
  if (map_) {
    const bool entities_changed = people_changed || !unpredicted_.empty() || removed;
    for (const std::string& key : unpredicted_) Predict(key, entities_.at(key), now, &update);
    unpredicted_.clear();
    if (entities_changed || map_changed) UpdatePlaces(now, &update);
    if (map_changed) CheckPredictions(now, &update);
  }
  stats_.entities = entities_.size();
  stats_.predictions = predictions_.size();
  return update;
}

void PredictionTracker::Predict(const std::string& key, const RobotEntity& entity, Timestamp now,
                                TrackerUpdate* update) {
  const std::string& entity_id = scene::EntityId(entity.entity);
  scene::Entities single;
  AddTo(entity.entity, entity_id, &single);
  StatusOr<ExtrapolationResult> result = Extrapolate(*map_, single, options_.extrapolation);
  if (!result.ok()) {
    Note(TrackerNote::Level::kWarning,
         "cannot extrapolate from " + key + ": " + result.status().message(), update);
    return;
  }
  for (const std::string& warning : result->warnings) {
    Note(TrackerNote::Level::kInfo, "extrapolation of " + key + ": " + warning, update);
  }
  const auto predicted = std::find_if(
      result->graph.submaps.begin(), result->graph.submaps.end(),
      [](const scene::Submap& submap) { return submap.kind != scene::SubmapKind::kObserved; });
  if (predicted == result->graph.submaps.end()) {
    Withdraw(key, update);  // e.g. the door is open now: nothing behind it to predict
    return;
  }
  auto [id, inserted] = submap_ids_.try_emplace(key, next_submap_id_);
  if (inserted) ++next_submap_id_;

  Prediction prediction;
  scene::SubmapNode& node = prediction.node;
  node.submap = *predicted;
  node.submap.id = id->second;
  node.submap.place = id->second;  // behind a door or up the stairs: a place of its own
  node.submap.confidence.clear();  // the wire carries the thresholded cells only
  node.state = scene::SubmapState::kPredicted;
  node.source_robot = entity.robot;
  node.source_entity = entity_id;
  node.stamp = now;
  prediction.added = AddedCells(node.submap, *map_);
  predictions_[key] = std::move(prediction);
  // Its edge to the place it opens from is set, and it is published, by UpdatePlaces().
}

void PredictionTracker::Withdraw(const std::string& key, TrackerUpdate* update) {
  const auto it = predictions_.find(key);
  if (it == predictions_.end()) return;
  Withdrawal(it->second.node.submap.id, update);
  predictions_.erase(it);
}

void PredictionTracker::UpdatePlaces(Timestamp now, TrackerUpdate* update) {
  if (entities_.empty()) {
    // Nothing splits the map and nobody walks in it: the one place would be the fused map
    // again, so none is published (and those published before are withdrawn).
    places_ = scene::SubmapGraph();
    place_of_.clear();
    PublishPlaces(now, update);
    return;
  }
  // Every entity at once, under its key (two robots may both have a "door_1").
  scene::Entities all;
  for (const auto& [key, entity] : entities_) AddTo(entity.entity, key, &all);
  StatusOr<ExtrapolationResult> result = Extrapolate(*map_, all, options_.extrapolation);
  if (!result.ok()) {
    Note(TrackerNote::Level::kWarning,
         "cannot split the fused map into places: " + result.status().message(), update);
    return;
  }
  places_ = scene::SubmapGraph();
  place_of_.clear();
  const scene::SubmapGraph& graph = result->graph;
  for (const scene::Submap& submap : graph.submaps) {
    if (submap.kind != scene::SubmapKind::kObserved) continue;
    scene::Submap place = submap;
    // Cells free only because people walk there are marked, not plain free.
    grid::OccupancyGrid& cells = place.navigable;
    for (int y = 0; y < cells.height(); ++y) {
      for (int x = 0; x < cells.width(); ++x) {
        if (cells.at(x, y) != grid::kFreeValue) continue;
        const auto index = result->conditionally_free.CellAt(cells.CellCenter(x, y));
        if (index && result->conditionally_free.at(index->x, index->y) == grid::kFreeValue &&
            map_->StateAt(index->x, index->y) != grid::CellState::kFree) {
          cells.at(x, y) = kConditionallyFree;
        }
      }
    }
    places_.submaps.push_back(std::move(place));
  }
  for (const scene::SubmapEdge& edge : graph.edges) {
    const scene::Submap* from = graph.Find(edge.from);
    const scene::Submap* to = graph.Find(edge.to);
    if (from == nullptr || to == nullptr) continue;
    if (to->kind == scene::SubmapKind::kObserved && from->kind == scene::SubmapKind::kObserved) {
      places_.edges.push_back(edge);
    } else if (from->kind == scene::SubmapKind::kObserved) {
      place_of_[edge.entity_id] = edge.from;  // the place this door or stairs opens from
    }
  }
  // Each prediction joins the place its entity opens from now (the map may have grown).
  for (auto& [key, prediction] : predictions_) {
    const auto place = place_of_.find(key);
    scene::SubmapEdge to_place;
    to_place.from = prediction.node.submap.id;
    to_place.to = place != place_of_.end() ? place->second : 0;
    const scene::Submap* observed = places_.Find(to_place.to);
    to_place.from_T_to =
        scene::RelativePose(prediction.node.submap.map_from_submap,
                            observed != nullptr ? observed->map_from_submap : Pose2{});
    to_place.entity_id = prediction.node.source_entity;
    if (prediction.node.edges.size() == 1 && prediction.node.edges[0].to == to_place.to) {
      continue;
    }
    prediction.node.edges = {to_place};
    Write(prediction.node, update);
  }
  PublishPlaces(now, update);
}

void PredictionTracker::CheckPredictions(Timestamp now, TrackerUpdate* update) {
  for (auto& [key, prediction] : predictions_) {
    // The fused map is one floor: a prediction for another floor (up the stairs) cannot be
    // checked against it, and stays predicted.
    if (prediction.judged || prediction.node.submap.elevation != 0.0) continue;
    const PredictionCheck check = CheckPrediction(prediction.added, *map_);
    scene::SubmapNode& node = prediction.node;
    const int64_t observed = check.true_free + check.false_free;
    if (observed == 0) continue;
    const auto precision = static_cast<float>(check.precision);
    const auto fraction = static_cast<float>(check.observed_fraction);
    bool changed = std::abs(precision - node.precision) >= 0.01F ||
                   std::abs(fraction - node.observed_fraction) >= 0.01F;
    node.precision = precision;
    node.observed_fraction = fraction;
    if (observed >= options_.min_observed_cells &&
        check.observed_fraction >= options_.judge_observed_fraction) {
      prediction.judged = true;
      changed = true;
      const bool right = check.precision >= options_.confirm_precision;
      node.state = right ? scene::SubmapState::kConfirmed : scene::SubmapState::kRetracted;
      char text[256];
      std::snprintf(
          text, sizeof(text), "prediction %u from %s %s: precision %.3f over %lld observed cells",
          static_cast<unsigned>(node.submap.id), key.c_str(), scene::SubmapStateName(node.state),
          check.precision, static_cast<long long>(observed));
      Note(TrackerNote::Level::kInfo, text, update);
      ++(right ? stats_.confirmed : stats_.retracted);
    }
    if (changed) {
      node.stamp = now;
      Write(node, update);
    }
  }
}

void PredictionTracker::PublishPlaces(Timestamp now, TrackerUpdate* update) {
  std::vector<scene::SubmapNode> places;
  for (const scene::Submap& place : places_.submaps) {
    scene::SubmapNode node;
    node.submap = place;
    node.submap.confidence.clear();
    node.state = scene::SubmapState::kObserved;
    node.stamp = now;
    for (const scene::SubmapEdge& edge : places_.edges) {
      if (edge.from == place.id || edge.to == place.id) {
        scene::SubmapEdge out = edge;
        if (edge.to == place.id) std::swap(out.from, out.to);  // edges start at this node
        out.from_T_to = Pose2{};                               // places share the fleet frame
        node.edges.push_back(out);
      }
    }
    for (const auto& [key, prediction] : predictions_) {
      const scene::SubmapNode& predicted = prediction.node;
      if (predicted.edges.empty() || predicted.edges[0].to != place.id) continue;
      scene::SubmapEdge edge;
      edge.from = place.id;
      edge.to = predicted.submap.id;
      edge.from_T_to = scene::RelativePose(place.map_from_submap, predicted.submap.map_from_submap);
      edge.entity_id = predicted.source_entity;
      node.edges.push_back(edge);
    }
    places.push_back(std::move(node));
  }
  // Only what changed goes out again; places the map no longer has are withdrawn.
  for (size_t k = 0; k < places.size(); ++k) {
    const bool same = k < published_places_.size() &&
                      published_places_[k].submap.navigable == places[k].submap.navigable &&
                      published_places_[k].submap.entity_ids == places[k].submap.entity_ids &&
                      published_places_[k].edges.size() == places[k].edges.size() &&
                      std::equal(places[k].edges.begin(), places[k].edges.end(),
                                 published_places_[k].edges.begin(),
                                 [](const scene::SubmapEdge& a, const scene::SubmapEdge& b) {
                                   return a.to == b.to && a.entity_id == b.entity_id;
                                 });
    if (!same) Write(places[k], update);
  }
  for (size_t k = places.size(); k < published_places_.size(); ++k) {
    Withdrawal(published_places_[k].submap.id, update);
  }
  published_places_ = std::move(places);
  stats_.places = published_places_.size();
}

void PredictionOptions::Describe(OptionsPrinter& out) const {
  out.Add("enabled", enabled);
  out.Nested("extrapolation", extrapolation);
  out.Add("judge_observed_fraction", judge_observed_fraction);
  out.Add("min_observed_cells", min_observed_cells);
  out.Add("confirm_precision", confirm_precision);
}

}  // namespace fleetmap::extrapolation
