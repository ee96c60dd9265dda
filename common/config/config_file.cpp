#include "common/config/config_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace fleetmap::config {
namespace {

constexpr const char* kRosParameters = "ros__parameters";

std::string Location(const std::string& path, const YAML::Node& node) {
  return path + ":" + std::to_string(node.Mark().line + 1);
}

// ROS 2 parameter names use `_` and `.` where the long options use `-`.
std::string OptionKey(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  std::replace(key.begin(), key.end(), '.', '-');
  return key;
}

// The settings of one map of keys (the whole plain file, or one ROS 2 node's ros__parameters),
// nested maps joining their keys with '-'.
class SectionReader {
 public:
  SectionReader(const std::string& path, bool for_every_node)
      : path_(path), for_every_node_(for_every_node) {}

  Status Read(const YAML::Node& map, const std::string& prefix) {
    for (const auto& entry : map) {
      const YAML::Node key = entry.first;
      const YAML::Node value = entry.second;
      if (!key.IsScalar() || key.Scalar().empty()) {
        return InvalidArgumentError(Location(path_, key) + ": a key must be a name");
      }
      const std::string name = prefix + OptionKey(key.Scalar());
      if (value.IsMap()) {
        FLEETMAP_RETURN_IF_ERROR(Read(value, name + "-"));
        continue;
      }
      if (const auto seen = first_seen_.find(name); seen != first_seen_.end()) {
        return InvalidArgumentError(Location(path_, key) + ": " + name +
                                    " is set twice (first at " + seen->second + ")");
      }
      first_seen_[name] = Location(path_, key);
      if (value.IsNull()) continue;  // `key: ~` leaves the option at its default
      ConfigSetting setting{name, {}, Location(path_, key), for_every_node_};
      if (value.IsScalar()) {
        setting.values.push_back(value.Scalar());
      } else {
        for (const YAML::Node& element : value) {
          if (!element.IsScalar()) {
            return InvalidArgumentError(Location(path_, element) + ": " + name +
                                        " takes a list of plain values, not of lists or maps");
          }
          setting.values.push_back(element.Scalar());
        }
      }
      settings_.push_back(std::move(setting));
    }
    return Status::Ok();
  }

  std::vector<ConfigSetting> Take() { return std::move(settings_); }

 private:
  const std::string& path_;
  bool for_every_node_;
  std::map<std::string, std::string> first_seen_;
  std::vector<ConfigSetting> settings_;
};

bool IsRosNodeSection(const YAML::Node& value) {
  return value.IsMap() && value[kRosParameters].IsDefined();
}

// How a ROS 2 params file's node key applies to `ros_node`: its own section (fleetmap_server,
// /fleetmap_server, /robot1/fleetmap_server, /**/fleetmap_server), the wildcard every node reads
// (/**, /*), or another node's.
enum class NodeMatch { kOwn, kEveryNode, kOther };

NodeMatch MatchNode(std::string key, const std::string& ros_node) {
  if (!key.empty() && key.front() == '/') key.erase(0, 1);
  if (key == "**" || key == "*") return NodeMatch::kEveryNode;
  if (key == ros_node) return NodeMatch::kOwn;
  const std::string tail = "/" + ros_node;
  const bool ends_with_node =
      key.size() > tail.size() && key.compare(key.size() - tail.size(), tail.size(), tail) == 0;
  return ends_with_node ? NodeMatch::kOwn : NodeMatch::kOther;
}

// A ROS 2 params file: the wildcard sections first, then this node's own, so that its own
// settings win over the wildcard's, as in ROS 2.
StatusOr<std::vector<ConfigSetting>> ReadRosParams(const std::string& path, const YAML::Node& root,
                                                   const std::string& ros_node, std::string* note) {
  // Kept apart rather than sorted: assigning a YAML::Node writes into the node it refers to.
  std::vector<YAML::Node> every_node_sections;
  std::vector<YAML::Node> own_sections;
  std::vector<std::string> nodes;
  for (const auto& entry : root) {
    const YAML::Node key_node = entry.first;
    const YAML::Node section = entry.second;
    const std::string key = key_node.Scalar();
    if (!IsRosNodeSection(section)) {
      return InvalidArgumentError(Location(path, key_node) + ": " + key +
                                  " is not a node's section (NODE: " + kRosParameters +
                                  ": ...) in a ROS 2 params file; put it under " + ros_node + ": " +
                                  kRosParameters + ":");
    }
    nodes.push_back(key);
    const NodeMatch match = MatchNode(key, ros_node);
    if (match == NodeMatch::kOther) continue;
    const YAML::Node parameters = section[kRosParameters];
    if (!parameters.IsMap() && !parameters.IsNull()) {
      return InvalidArgumentError(Location(path, parameters) + ": " + key + "'s " + kRosParameters +
                                  " is not a map of parameters");
    }
    (match == NodeMatch::kEveryNode ? every_node_sections : own_sections).push_back(parameters);
  }
  if (every_node_sections.empty() && own_sections.empty()) {
    std::string listed;
    for (const std::string& node : nodes) listed += (listed.empty() ? "" : ", ") + node;
    if (note != nullptr) {
      *note = path + ": a ROS 2 params file with no section for " + ros_node +
              " (nor /**), so no settings from it; it has " + listed;
    }
    return std::vector<ConfigSetting>{};
  }
  std::vector<ConfigSetting> settings;
  for (const bool for_every_node : {true, false}) {
    for (const YAML::Node& parameters : for_every_node ? every_node_sections : own_sections) {
      if (parameters.IsNull()) continue;
      SectionReader reader(path, for_every_node);
      FLEETMAP_RETURN_IF_ERROR(reader.Read(parameters, ""));
      for (ConfigSetting& setting : reader.Take()) settings.push_back(std::move(setting));
    }
  }
  return settings;
}

}  // namespace

StatusOr<std::vector<ConfigSetting>> ReadConfigFile(const std::string& path,
                                                    const std::string& ros_node,
                                                    std::string* note) {
  std::ifstream file(path);
  if (!file) {
    return InvalidArgumentError(path + ": cannot be read (" + std::strerror(errno) + ")");
  }
  std::stringstream text;
  text << file.rdbuf();
  YAML::Node root;
  try {
    root = YAML::Load(text.str());
  } catch (const YAML::ParserException& error) {
    return InvalidArgumentError(path + ":" + std::to_string(error.mark.line + 1) + ":" +
                                std::to_string(error.mark.column + 1) + ": not YAML: " + error.msg);
  }
  if (root.IsNull()) return std::vector<ConfigSetting>{};
  if (!root.IsMap()) {
    return InvalidArgumentError(path + ": a config file is a map of option names to values");
  }
  const bool ros_params = std::any_of(
      root.begin(), root.end(), [](const auto& entry) { return IsRosNodeSection(entry.second); });
  if (ros_params) return ReadRosParams(path, root, ros_node, note);
  SectionReader reader(path, /*for_every_node=*/false);
  FLEETMAP_RETURN_IF_ERROR(reader.Read(root, ""));
  return reader.Take();
}

}  // namespace fleetmap::config
