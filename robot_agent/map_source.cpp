#include "robot_agent/map_source.hpp"

#include <spdlog/spdlog.h>

#include "common/grid/map_io.hpp"

namespace fleetmap::agent {

StatusOr<std::unique_ptr<FileMapSource>> FileMapSource::Create(std::string path) {
  std::unique_ptr<FileMapSource> source(new FileMapSource(std::move(path)));
  FLEETMAP_ASSIGN_OR_RETURN(grid::LoadedMap loaded, grid::LoadMap(source->path_));
  std::error_code error;
  source->mtime_ = std::filesystem::last_write_time(source->path_, error);
  source->pending_ = std::move(loaded.grid);
  return source;
}

std::optional<grid::OccupancyGrid> FileMapSource::Poll() {
  if (pending_) {
    std::optional<grid::OccupancyGrid> first = std::move(pending_);
    pending_.reset();
    return first;
  }
  std::error_code error;
  const auto mtime = std::filesystem::last_write_time(path_, error);
  if (error || mtime == mtime_) return std::nullopt;
  mtime_ = mtime;  // a broken file is reported once, not at every poll
  StatusOr<grid::LoadedMap> loaded = grid::LoadMap(path_);
  if (!loaded.ok()) {
    spdlog::warn("keeping the previous map: {}", loaded.status().message());
    return std::nullopt;
  }
  return std::move(loaded->grid);
}

StatusOr<std::unique_ptr<TopicMapSource>> TopicMapSource::Create(
    transport::Participant& participant, const std::string& topic) {
  std::unique_ptr<TopicMapSource> source(new TopicMapSource(topic));
  FLEETMAP_ASSIGN_OR_RETURN(source->reader_,
                            transport::OccupancyGridReader::Create(participant, topic));
  FLEETMAP_ASSIGN_OR_RETURN(source->updates_,
                            transport::MapUpdateReader::Create(participant, topic + "_updates"));
  return source;
}

std::optional<grid::OccupancyGrid> TopicMapSource::Poll() {
  bool changed = false;
  for (StatusOr<transport::MapMessage>& message : reader_->Drain()) {
    if (!message.ok()) {
      spdlog::warn("dropped a map from {}: {}", topic_, message.status().message());
      continue;
    }
    current_ = std::move(message->grid);  // a full map replaces everything before it
    changed = true;
  }
  for (StatusOr<transport::MapUpdate>& update : updates_->Drain()) {
    if (!update.ok()) {
      spdlog::warn("dropped a map update from {}_updates: {}", topic_, update.status().message());
      continue;
    }
    if (!current_) continue;  // an update means nothing before the first full map
    if (const Status applied = transport::ApplyMapUpdate(*update, &*current_); !applied.ok()) {
      spdlog::warn("dropped a map update from {}_updates: {}", topic_, applied.message());
      continue;
    }
    changed = true;
  }
  if (!changed) return std::nullopt;
  return current_;
}

}  // namespace fleetmap::agent
