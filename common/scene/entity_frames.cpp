#include "common/scene/entity_frames.hpp"

#include <cmath>

namespace fleetmap::scene {
namespace {

struct ToFleet {
  const Transform2& fleet_from_map;

  Vector2 Direction(const Vector2& direction) const { return fleet_from_map.linear() * direction; }
  double Heading(double heading) const {
    const Vector2 direction = Direction({std::cos(heading), std::sin(heading)});
    return std::atan2(direction.y(), direction.x());
  }

  Entity operator()(DoorEntity door) const {
    door.hinge = fleet_from_map * door.hinge;
    door.latch = fleet_from_map * door.latch;
    door.opening_direction = Direction(door.opening_direction);
    return door;
  }
  Entity operator()(StairsEntity stairs) const {
    stairs.position = fleet_from_map * stairs.position;
    stairs.ascending = Direction(stairs.ascending);
    return stairs;
  }
  Entity operator()(PersonTrack track) const {
    for (TrackPoint& point : track.points) {
      point.position = fleet_from_map * point.position;
      point.heading = Heading(point.heading);
    }
    return track;
  }
};

bool Same(const DoorEntity& a, const DoorEntity& b) {
  return a.id == b.id && a.hinge == b.hinge && a.latch == b.latch &&
         a.opening_direction == b.opening_direction && a.open == b.open;
}

bool Same(const StairsEntity& a, const StairsEntity& b) {
  return a.id == b.id && a.position == b.position && a.ascending == b.ascending &&
         a.step_width == b.step_width && a.next_floor_height == b.next_floor_height &&
         a.run_length == b.run_length;
}

bool Same(const PersonTrack& a, const PersonTrack& b) {
  if (a.id != b.id || a.dominant_side != b.dominant_side || a.left_view != b.left_view ||
      a.entered_view != b.entered_view || a.points.size() != b.points.size()) {
    return false;
  }
  for (size_t i = 0; i < a.points.size(); ++i) {
    if (a.points[i].stamp != b.points[i].stamp || a.points[i].position != b.points[i].position ||
        a.points[i].heading != b.points[i].heading) {
      return false;
    }
  }
  return true;
}

}  // namespace

const std::string& EntityId(const Entity& entity) {
  return std::visit([](const auto& kind) -> const std::string& { return kind.id; }, entity);
}

Entity ToFleetFrame(const Entity& entity, const Transform2& fleet_from_map) {
  return std::visit(ToFleet{fleet_from_map}, entity);
}

bool SameEntity(const Entity& a, const Entity& b) {
  if (a.index() != b.index()) return false;
  return std::visit(
      [&b](const auto& entity) {
        return Same(entity, std::get<std::decay_t<decltype(entity)>>(b));
      },
      a);
}

}  // namespace fleetmap::scene
