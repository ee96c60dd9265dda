#include "robot_agent/map_source.hpp"

#include <spdlog/spdlog.h>

#include "common/grid/map_io.hpp"

namespace fleetmap::agent {

StatusOr<std::unique_ptr<FileMapSource>> FileMapSource::Create(std::string path,
                                                               grid::MapLoadOptions options) {
  std::unique_ptr<FileMapSource> source(new FileMapSource(std::move(path), std::move(options)));
  FLEETMAP_ASSIGN_OR_RETURN(source->pending_, source->Read());
  return source;
}

FileMapSource::Signatures FileMapSource::Now() const {
  return {FileSignature::Of(path_), FileSignature::Of(image_path_)};
}

StatusOr<grid::OccupancyGrid> FileMapSource::Read() {
  const FileSignature yaml = FileSignature::Of(path_);
  StatusOr<grid::MapMetadata> metadata = grid::ReadMapYaml(path_, options_);
  if (metadata.ok()) image_path_ = metadata->image_path;
  const Signatures before{yaml, FileSignature::Of(image_path_)};
  StatusOr<grid::OccupancyGrid> grid =
      metadata.ok() ? grid::LoadMapImage(*metadata, options_) : metadata.status();
  read_.reset();
  if (Now() == before) read_ = before;
  if (!grid.ok() && grid.status().code() == StatusCode::kNotFound && metadata.ok()) {
    return NotFoundError(grid.status().message() + " (the image of " + path_ + ")");
  }
  return grid;
}

std::optional<grid::OccupancyGrid> FileMapSource::Poll() {
  if (pending_) {
    std::optional<grid::OccupancyGrid> first = std::move(pending_);
    pending_.reset();
    return first;
  }
  if (read_ && *read_ == Now()) return std::nullopt;  // nothing changed since the last read
  StatusOr<grid::OccupancyGrid> grid = Read();
  if (!read_) {
    // A file changed while it was read (an editor is writing it): read again at the next poll.
    spdlog::debug("{} changed while being read; reading it again", path_);
    return std::nullopt;
  }
  if (!grid.ok()) {
    if (grid.status().message() != problem_) {
      problem_ = grid.status().message();
      spdlog::warn("keeping the previous map until {} can be read: {}", path_, problem_);
    }
    return std::nullopt;
  }
  if (!problem_.empty()) spdlog::info("{} can be read again", path_);
  problem_.clear();
  return std::move(grid).value();
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
