#pragma once

// Known fleet_from_map transforms, one per robot, from a YAML file shared by the fleet:
//
//   robots:
//     alpha: [0.0, 0.0, 0.0]      # x (m), y (m), yaw (rad) of alpha's map frame in the fleet
//     beta:  [40.0, 0.0, 0.0]
//
// Agents take their own entry (`--transforms`); the server uses them for robots on the grid wire
// and checks tile-wire robots against them.

#include <map>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"

namespace fleetmap::config {

using FleetTransforms = std::map<RobotId, Pose2>;

// Errors name the file and the entry: missing file, YAML syntax, no `robots` map, a robot name
// that is not a ROS name token, a value that is not three finite numbers.
StatusOr<FleetTransforms> LoadFleetTransforms(const std::string& path);

}  // namespace fleetmap::config
