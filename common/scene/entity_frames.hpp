#pragma once

// Entities arrive in each robot's own map frame; the server predicts in the fleet frame.

#include "common/core/types.hpp"
#include "common/scene/entities.hpp"

namespace fleetmap::scene {

// The entity with every point and direction taken from its map frame to the fleet frame.
Entity ToFleetFrame(const Entity& entity, const Transform2& fleet_from_map);

// True when two entities say the same thing (same kind, id and values), so a re-sent entity does
// not reset a prediction that is being checked.
bool SameEntity(const Entity& a, const Entity& b);

}  // namespace fleetmap::scene
