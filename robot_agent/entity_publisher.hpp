#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::agent {

// Publishes the entities a robot recognised (doors, stairs, people's tracks) on
// rt/fleetmap/entities, one instance per entity, from an entities JSON file
// (docs/extrapolation.md) that the robot's perception rewrites: the file is re-read when it
// changes, new and changed entities are written, and entities gone from the file are disposed.
// A file that does not parse keeps the entities already published (and is reported once); an
// unusable entry is skipped with a warning naming it. Call from one thread.
class EntityPublisher {
 public:
  static StatusOr<std::unique_ptr<EntityPublisher>> Create(transport::Participant& participant,
                                                           RobotId robot, std::string path);
  ~EntityPublisher();

  // Reads the file if it changed since the last poll and publishes the difference.
  Status Poll();
  size_t published() const { return published_.size(); }

 private:
  EntityPublisher(RobotId robot, std::string path)
      : robot_(std::move(robot)), path_(std::move(path)) {}

  RobotId robot_;
  std::string path_;
  std::filesystem::file_time_type mtime_{};
  std::unique_ptr<transport::EntityWriter> writer_;
  std::map<std::string, transport::EntityMessage> published_;  // by entity id
};

}  // namespace fleetmap::agent
