#include "common/config/fleet_transforms.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>

namespace fleetmap::config {

StatusOr<FleetTransforms> LoadFleetTransforms(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return NotFoundError(path + ": no such file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& exception) {
    return InvalidArgumentError(path + ": not valid YAML: " + exception.what());
  }
  const YAML::Node robots = root["robots"];
  if (!robots || !robots.IsMap()) {
    return InvalidArgumentError(path + ": needs a `robots` map of name: [x, y, yaw]");
  }
  FleetTransforms transforms;
  for (const auto& entry : robots) {
    const std::string name = entry.first.as<std::string>("");
    if (!IsValidRobotName(name)) {
      return InvalidArgumentError(path + ": \"" + name + "\" is not a valid robot name");
    }
    const YAML::Node value = entry.second;
    if (!value.IsSequence() || value.size() != 3) {
      return InvalidArgumentError(path + ": robots." + name + " must be [x, y, yaw]");
    }
    double numbers[3];
    for (size_t i = 0; i < 3; ++i) {
      try {
        numbers[i] = value[i].as<double>();
      } catch (const YAML::Exception&) {
        return InvalidArgumentError(path + ": robots." + name + "[" + std::to_string(i) +
                                    "] is not a number");
      }
      if (!std::isfinite(numbers[i])) {
        return InvalidArgumentError(path + ": robots." + name + " is not finite");
      }
    }
    transforms[RobotId{name}] = Pose2{numbers[0], numbers[1], numbers[2]};
  }
  return transforms;
}

}  // namespace fleetmap::config
