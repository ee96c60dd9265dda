#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/map_update_reader.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::agent {

// Where an agent's grid comes from. Poll() is called from the agent's loop; it returns the grid
// when it changed since the last call. A source never stops the agent: a broken update is logged
// and the previous map stays.
class MapSource {
 public:
  virtual ~MapSource() = default;
  virtual std::optional<grid::OccupancyGrid> Poll() = 0;
  virtual std::string Describe() const = 0;
};

// A ROS map_server YAML, re-read when its modification time changes. Create fails when the file
// cannot be loaded at start (that is the user's error to fix, exit code 2).
class FileMapSource : public MapSource {
 public:
  static StatusOr<std::unique_ptr<FileMapSource>> Create(std::string path);
  std::optional<grid::OccupancyGrid> Poll() override;
  std::string Describe() const override { return path_; }

 private:
  explicit FileMapSource(std::string path) : path_(std::move(path)) {}

  std::string path_;
  std::optional<grid::OccupancyGrid> pending_;  // loaded at Create, handed out by the first Poll
  std::filesystem::file_time_type mtime_;
};

// nav_msgs/OccupancyGrid samples on a DDS topic (a ROS 2 SLAM's /map is rt/map), patched by the
// map_msgs/OccupancyGridUpdate samples on <topic>_updates (/map_updates) between full maps.
class TopicMapSource : public MapSource {
 public:
  static StatusOr<std::unique_ptr<TopicMapSource>> Create(transport::Participant& participant,
                                                          const std::string& topic);
  std::optional<grid::OccupancyGrid> Poll() override;
  std::string Describe() const override { return topic_; }

 private:
  explicit TopicMapSource(std::string topic) : topic_(std::move(topic)) {}

  std::string topic_;
  std::unique_ptr<transport::OccupancyGridReader> reader_;
  std::unique_ptr<transport::MapUpdateReader> updates_;
  std::optional<grid::OccupancyGrid> current_;  // the last full map with its updates applied
};

}  // namespace fleetmap::agent
