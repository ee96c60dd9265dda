#include "common/scene/submap_graph.hpp"

namespace fleetmap::scene {

std::string_view SubmapKindName(SubmapKind kind) {
  switch (kind) {
    case SubmapKind::kObserved:
      return "observed";
    case SubmapKind::kPredictedStairs:
      return "predicted_stairs";
    case SubmapKind::kPredictedDoor:
      return "predicted_door";
  }
  return "unknown";
}

const Submap* SubmapGraph::Find(uint32_t id) const {
  for (const Submap& submap : submaps) {
    if (submap.id == id) return &submap;
  }
  return nullptr;
}

Pose2 RelativePose(const Pose2& map_from_from, const Pose2& map_from_to) {
  return Pose2::FromTransform(map_from_from.ToTransform().inverse() * map_from_to.ToTransform());
}

const char* SubmapStateName(SubmapState state) {
  switch (state) {
    case SubmapState::kObserved:
      return "observed";
    case SubmapState::kPredicted:
      return "predicted";
    case SubmapState::kConfirmed:
      return "confirmed";
    case SubmapState::kRetracted:
      return "retracted";
  }
  return "unknown";
}

}  // namespace fleetmap::scene
