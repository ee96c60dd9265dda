#include "server/prediction_worker.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "common/extrapolation/prediction_check.hpp"
#include "common/scene/entity_frames.hpp"

namespace fleetmap::server {
namespace {

std::string KeyOf(const RobotId& robot, const std::string& entity_id) {
  return robot.value + "/" + entity_id;
}

bool PredictsASubmap(const transport::EntityMessage& entity) {
  return !std::holds_alternative<scene::PersonTrack>(entity.entity);
}

scene::Entities Single(const transport::EntityMessage& message) {
  scene::Entities entities;
  std::visit(
      [&entities](const auto& entity) {
        using T = std::decay_t<decltype(entity)>;
        if constexpr (std::is_same_v<T, scene::DoorEntity>) {
          entities.doors.push_back(entity);
        } else if constexpr (std::is_same_v<T, scene::StairsEntity>) {
          entities.stairs.push_back(entity);
        } else {
          entities.people.push_back(entity);
        }
      },
      message.entity);
  return entities;
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

StatusOr<std::unique_ptr<PredictionWorker>> PredictionWorker::Create(
    transport::Participant& participant, const PredictionOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate().WithContext("map extrapolation"));
  std::unique_ptr<PredictionWorker> worker(new PredictionWorker(options));
  FLEETMAP_ASSIGN_OR_RETURN(worker->writer_, transport::SubmapWriter::Create(participant));
  return worker;
}

PredictionWorker::~PredictionWorker() {
  Stop();
  writer_.reset();
}

void PredictionWorker::Start() {
  thread_ = std::thread([this] { Loop(); });
}

void PredictionWorker::Stop() {
  stop_.store(true);
  wake_up_->Notify();
  if (thread_.joinable()) thread_.join();
}

void PredictionWorker::SubmitEntity(transport::EntityMessage entity) {
  inputs_.Push({Input::Kind::kEntity, std::move(entity), {}});
  wake_up_->Notify();
}

void PredictionWorker::RemoveEntity(const RobotId& robot, const std::string& entity_id) {
  Input input;
  input.kind = Input::Kind::kRemoved;
  input.entity.robot = robot;
  scene::DoorEntity key_only;
  key_only.id = entity_id;
  input.entity.entity = key_only;
  inputs_.Push(std::move(input));
  wake_up_->Notify();
}

void PredictionWorker::SubmitMap(grid::OccupancyGrid map) {
  inputs_.Push({Input::Kind::kMap, {}, std::move(map)});
  wake_up_->Notify();
}

PredictionStats PredictionWorker::stats() const {
  std::lock_guard lock(stats_mutex_);
  return stats_;
}

void PredictionWorker::Loop() {
  while (!stop_.load()) {
    wake_up_->WaitFor(std::chrono::milliseconds(100));
    HandleInputs();
  }
}

void PredictionWorker::HandleInputs() {
  std::vector<Input> inputs = inputs_.Drain();
  if (inputs.empty()) return;
  bool map_changed = false;
  bool people_changed = false;
  bool removed = false;
  // Only the newest map matters; entities in arrival order.
  for (Input& input : inputs) {
    if (input.kind == Input::Kind::kMap) {
      map_ = std::move(input.map);
      map_changed = true;
      continue;
    }
    const std::string key = KeyOf(input.entity.robot, input.entity.entity_id());
    if (input.kind == Input::Kind::kRemoved) {
      const auto it = entities_.find(key);
      if (it == entities_.end()) continue;
      removed = true;
      entities_.erase(it);
      std::erase(unpredicted_, key);
      Withdraw(key);
      continue;
    }
    const auto it = entities_.find(key);
    if (it != entities_.end() && SameEntity(it->second.entity, input.entity.entity)) continue;
    if (it != entities_.end() && PredictsASubmap(it->second) != PredictsASubmap(input.entity)) {
      Withdraw(key);  // an id reused for another kind of entity
      people_changed = true;
    }
    people_changed |= !PredictsASubmap(input.entity);
    if (PredictsASubmap(input.entity) &&
        std::find(unpredicted_.begin(), unpredicted_.end(), key) == unpredicted_.end()) {
      unpredicted_.push_back(key);
    }
    entities_[key] = std::move(input.entity);
  }
  if (map_) {
    const bool entities_changed = people_changed || !unpredicted_.empty() || removed;
    for (const std::string& key : unpredicted_) Predict(key, entities_.at(key));
    unpredicted_.clear();
    if (entities_changed || map_changed) UpdatePlaces();
    if (map_changed) CheckPredictions();
  }
  std::lock_guard lock(stats_mutex_);
  stats_.entities = entities_.size();
  stats_.predictions = predictions_.size();
}

void PredictionWorker::Predict(const std::string& key, const transport::EntityMessage& entity) {
  StatusOr<extrapolation::ExtrapolationResult> result =
      extrapolation::Extrapolate(*map_, Single(entity), options_.extrapolation);
  if (!result.ok()) {
    spdlog::warn("server: cannot extrapolate from {}: {}", key, result.status().message());
    return;
  }
  for (const std::string& warning : result->warnings) {
    spdlog::info("server: extrapolation of {}: {}", key, warning);
  }
  const auto predicted = std::find_if(
      result->graph.submaps.begin(), result->graph.submaps.end(),
      [](const scene::Submap& submap) { return submap.kind != scene::SubmapKind::kObserved; });
  if (predicted == result->graph.submaps.end()) {
    Withdraw(key);  // e.g. the door is open now: nothing behind it to predict
    return;
  }
  auto [id, inserted] = submap_ids_.try_emplace(key, next_submap_id_);
  if (inserted) ++next_submap_id_;

  Prediction prediction;
  transport::SubmapMessage& message = prediction.message;
  message.submap = *predicted;
  message.submap.id = id->second;
  message.submap.place = id->second;  // behind a door or up the stairs: a place of its own
  message.submap.confidence.clear();  // the wire carries the thresholded cells only
  message.state = scene::SubmapState::kPredicted;
  message.source_robot = entity.robot.value;
  message.source_entity = entity.entity_id();
  message.stamp = Clock::now();
  prediction.added = AddedCells(message.submap, *map_);
  predictions_[key] = std::move(prediction);
  // Its edge to the place it opens from is set, and it is published, by UpdatePlaces().
}

void PredictionWorker::Withdraw(const std::string& key) {
  const auto it = predictions_.find(key);
  if (it == predictions_.end()) return;
  transport::SubmapMessage removed;
  removed.submap.id = it->second.message.submap.id;
  if (Status disposed = writer_->Dispose(removed); !disposed.ok()) {
    spdlog::warn("server: {}", disposed.message());
  }
  predictions_.erase(it);
}

void PredictionWorker::UpdatePlaces() {
  if (entities_.empty()) {
    // Nothing splits the map and nobody walks in it: the one place would be rt/fleetmap/map
    // again, so none is published (and those published before are withdrawn).
    places_ = scene::SubmapGraph();
    place_of_.clear();
    PublishPlaces();
    return;
  }
  // Every entity at once, under its server key (two robots may both have a "door_1").
  scene::Entities all;
  for (const auto& [key, message] : entities_) {
    std::visit(
        [&all, &key](auto entity) {
          entity.id = key;
          using T = std::decay_t<decltype(entity)>;
          if constexpr (std::is_same_v<T, scene::DoorEntity>) {
            all.doors.push_back(std::move(entity));
          } else if constexpr (std::is_same_v<T, scene::StairsEntity>) {
            all.stairs.push_back(std::move(entity));
          } else {
            all.people.push_back(std::move(entity));
          }
        },
        message.entity);
  }
  StatusOr<extrapolation::ExtrapolationResult> result =
      extrapolation::Extrapolate(*map_, all, options_.extrapolation);
  if (!result.ok()) {
    spdlog::warn("server: cannot split the fused map into places: {}", result.status().message());
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
    to_place.from = prediction.message.submap.id;
    to_place.to = place != place_of_.end() ? place->second : 0;
    const scene::Submap* observed = places_.Find(to_place.to);
    to_place.from_T_to =
        scene::RelativePose(prediction.message.submap.map_from_submap,
                            observed != nullptr ? observed->map_from_submap : Pose2{});
    to_place.entity_id = prediction.message.source_entity;
    if (prediction.message.edges.size() == 1 && prediction.message.edges[0].to == to_place.to) {
      continue;
    }
    prediction.message.edges = {to_place};
    Publish(prediction.message);
  }
  PublishPlaces();
}

void PredictionWorker::CheckPredictions() {
  for (auto& [key, prediction] : predictions_) {
    // The fused map is one floor: a prediction for another floor (up the stairs) cannot be
    // checked against it, and stays predicted.
    if (prediction.judged || prediction.message.submap.elevation != 0.0) continue;
    const extrapolation::PredictionCheck check =
        extrapolation::CheckPrediction(prediction.added, *map_);
    transport::SubmapMessage& message = prediction.message;
    const int64_t observed = check.true_free + check.false_free;
    if (observed == 0) continue;
    const auto precision = static_cast<float>(check.precision);
    const auto fraction = static_cast<float>(check.observed_fraction);
    bool changed = std::abs(precision - message.precision) >= 0.01F ||
                   std::abs(fraction - message.observed_fraction) >= 0.01F;
    message.precision = precision;
    message.observed_fraction = fraction;
    if (observed >= options_.min_observed_cells &&
        check.observed_fraction >= options_.judge_observed_fraction) {
      prediction.judged = true;
      changed = true;
      const bool right = check.precision >= options_.confirm_precision;
      message.state = right ? scene::SubmapState::kConfirmed : scene::SubmapState::kRetracted;
      spdlog::info("server: prediction {} from {} {}: precision {:.3f} over {} observed cells",
                   message.submap.id, key, scene::SubmapStateName(message.state), check.precision,
                   observed);
      std::lock_guard lock(stats_mutex_);
      ++(right ? stats_.confirmed : stats_.retracted);
    }
    if (changed) {
      message.stamp = Clock::now();
      Publish(message);
    }
  }
}

void PredictionWorker::PublishPlaces() {
  std::vector<transport::SubmapMessage> places;
  for (const scene::Submap& place : places_.submaps) {
    transport::SubmapMessage message;
    message.submap = place;
    message.submap.confidence.clear();
    message.state = scene::SubmapState::kObserved;
    message.stamp = Clock::now();
    for (const scene::SubmapEdge& edge : places_.edges) {
      if (edge.from == place.id || edge.to == place.id) {
        scene::SubmapEdge out = edge;
        if (edge.to == place.id) std::swap(out.from, out.to);  // edges start at this node
        out.from_T_to = Pose2{};                               // places share the fleet frame
        message.edges.push_back(out);
      }
    }
    for (const auto& [key, prediction] : predictions_) {
      const transport::SubmapMessage& predicted = prediction.message;
      if (predicted.edges.empty() || predicted.edges[0].to != place.id) continue;
      scene::SubmapEdge edge;
      edge.from = place.id;
      edge.to = predicted.submap.id;
      edge.from_T_to = scene::RelativePose(place.map_from_submap, predicted.submap.map_from_submap);
      edge.entity_id = predicted.source_entity;
      message.edges.push_back(edge);
    }
    places.push_back(std::move(message));
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
    if (!same) Publish(places[k]);
  }
  for (size_t k = places.size(); k < published_places_.size(); ++k) {
    if (Status disposed = writer_->Dispose(published_places_[k]); !disposed.ok()) {
      spdlog::warn("server: {}", disposed.message());
    }
  }
  published_places_ = std::move(places);
  std::lock_guard lock(stats_mutex_);
  stats_.places = published_places_.size();
}

void PredictionWorker::Publish(const transport::SubmapMessage& message) {
  StatusOr<size_t> written = writer_->Write(message);
  if (!written.ok()) {
    spdlog::warn("server: sub-map {}: {}", message.submap.id, written.status().message());
    return;
  }
  std::lock_guard lock(stats_mutex_);
  ++stats_.submaps_published;
}

}  // namespace fleetmap::server
