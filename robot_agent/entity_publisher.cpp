#include "robot_agent/entity_publisher.hpp"

#include <spdlog/spdlog.h>

#include <fstream>
#include <sstream>

#include "common/extrapolation/entities_json.hpp"

namespace fleetmap::agent {
namespace {

// Every entity of the file as one message each, by id.
std::map<std::string, transport::EntityMessage> Messages(const RobotId& robot,
                                                         const scene::Entities& entities) {
  std::map<std::string, transport::EntityMessage> messages;
  const auto add = [&](const auto& entity) {
    transport::EntityMessage message;
    message.robot = robot;
    message.stamp = Clock::now();
    message.entity = entity;
    messages[entity.id] = std::move(message);
  };
  for (const auto& door : entities.doors) add(door);
  for (const auto& stairs : entities.stairs) add(stairs);
  for (const auto& track : entities.people) add(track);
  return messages;
}

}  // namespace

StatusOr<std::unique_ptr<EntityPublisher>> EntityPublisher::Create(
    transport::Participant& participant, RobotId robot, std::string path) {
  std::unique_ptr<EntityPublisher> self(new EntityPublisher(std::move(robot), std::move(path)));
  if (!std::filesystem::exists(self->path_)) {
    return NotFoundError(self->path_ + ": no such entities file");
  }
  FLEETMAP_ASSIGN_OR_RETURN(self->writer_, transport::EntityWriter::Create(participant));
  return self;
}

EntityPublisher::~EntityPublisher() = default;

Status EntityPublisher::Poll() {
  std::error_code error;
  const auto mtime = std::filesystem::last_write_time(path_, error);
  if (error || mtime == mtime_) return Status::Ok();
  mtime_ = mtime;  // a broken file is reported once, not at every poll
  std::ifstream in(path_);
  std::stringstream text;
  text << in.rdbuf();
  StatusOr<extrapolation::ParsedEntities> parsed =
      extrapolation::ParseEntitiesJson(text.str(), path_);
  if (!parsed.ok()) {
    return parsed.status().WithContext("keeping the entities already published");
  }
  for (const std::string& warning : parsed->warnings) {
    spdlog::warn("{}: {}", robot_.value, warning);
  }
  std::map<std::string, transport::EntityMessage> current = Messages(robot_, parsed->entities);
  for (const auto& [id, message] : published_) {
    if (current.count(id) > 0) continue;
    FLEETMAP_RETURN_IF_ERROR(writer_->Dispose(message));
  }
  for (const auto& [id, message] : current) {
    StatusOr<size_t> written = writer_->Write(message);
    if (!written.ok())
      spdlog::warn("{}: entity {}: {}", robot_.value, id, written.status().message());
  }
  published_ = std::move(current);
  return Status::Ok();
}

}  // namespace fleetmap::agent
