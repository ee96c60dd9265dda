#include "common/config/shard_file.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>

namespace fleetmap::config {

StatusOr<ShardPlan> LoadShardPlan(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return NotFoundError(path + ": no such file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& exception) {
    return InvalidArgumentError(path + ": not valid YAML: " + exception.what());
  }
  const YAML::Node shards = root["shards"];
  if (!shards || !shards.IsMap() || shards.size() == 0) {
    return InvalidArgumentError(path + ": needs a `shards` map of name: [X0, Y0, X1, Y1]");
  }
  std::vector<ShardRegion> regions;
  for (const auto& entry : shards) {
    const std::string name = entry.first.as<std::string>("");
    const YAML::Node value = entry.second;
    if (!value.IsSequence() || value.size() != 4) {
      return InvalidArgumentError(path + ": shards." + name +
                                  " must be [X0, Y0, X1, Y1] (metres in the fleet frame)");
    }
    double corners[4];
    for (size_t i = 0; i < 4; ++i) {
      try {
        corners[i] = value[i].as<double>();
      } catch (const YAML::Exception&) {
        return InvalidArgumentError(path + ": shards." + name + "[" + std::to_string(i) +
                                    "] is not a number");
      }
    }
    regions.push_back(ShardRegion{name, corners[0], corners[1], corners[2], corners[3]});
  }
  std::map<RobotId, std::string> homes;
  if (const YAML::Node robots = root["robots"]) {
    if (!robots.IsMap()) {
      return InvalidArgumentError(path + ": `robots` must map robot names to shards");
    }
    for (const auto& entry : robots) {
      homes[RobotId{entry.first.as<std::string>("")}] = entry.second.as<std::string>("");
    }
  }
  StatusOr<ShardPlan> plan = ShardPlan::Create(std::move(regions), std::move(homes));
  if (!plan.ok()) return InvalidArgumentError(path + ": " + plan.status().message());
  return plan;
}

}  // namespace fleetmap::config
