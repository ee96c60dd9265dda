#include "server/session_archive.hpp"

#include "common/transport/vmap_file.hpp"

namespace fleetmap::server {
namespace {

int64_t Nanoseconds(Timestamp stamp) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(stamp.time_since_epoch()).count();
}

Timestamp FromNanoseconds(int64_t ns) {
  return Timestamp(std::chrono::duration_cast<Clock::duration>(std::chrono::nanoseconds(ns)));
}

}  // namespace

StatusOr<std::vector<std::string>> SessionArchive::Restore() {
  std::vector<std::string> warnings;
  if (store_ == nullptr) return warnings;
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<store::SessionRecord> records, store_->Sessions());
  for (const store::SessionRecord& record : records) {
    StatusOr<vector_map::TiledVectorMap> map = transport::DecodeVmap(
        record.payload, store_->path() + " session " + std::to_string(record.id));
    if (!map.ok()) {
      warnings.push_back(map.status().message());
      continue;
    }
    Keep({record.id, record.robot, FromNanoseconds(record.started_ns),
          FromNanoseconds(record.ended_ns), *std::move(map)});
    next_memory_id_ = std::max(next_memory_id_, record.id + 1);
  }
  return warnings;
}

void SessionArchive::RecordTile(const RobotId& robot, const TileId& tile,
                                const vector_map::VectorMap& map, Timestamp stamp) {
  auto& sessions = closed_.count(robot) > 0 ? held_ : open_;
  auto [it, inserted] = sessions.try_emplace(robot);
  MappingSession& session = it->second;
  if (inserted) {
    session.robot = robot;
    session.started = stamp;
    session.map.tile_size = tile_size_;
  }
  session.map.tiles[tile] = map;
}

void SessionArchive::RemoveTile(const RobotId& robot, const TileId& tile) {
  for (auto* sessions : {&open_, &held_}) {
    const auto it = sessions->find(robot);
    if (it != sessions->end()) it->second.map.tiles.erase(tile);
  }
}

void SessionArchive::Rejoin(const RobotId& robot) {
  closed_.erase(robot);
  const auto held = held_.find(robot);
  if (held == held_.end()) return;
  open_.emplace(robot, std::move(held->second));
  held_.erase(held);
}

StatusOr<std::optional<MappingSession>> SessionArchive::EndSession(const RobotId& robot,
                                                                   Timestamp ended) {
  held_.erase(robot);  // late samples of a session that already ended
  closed_.insert(robot);
  const auto it = open_.find(robot);
  if (it == open_.end()) return std::optional<MappingSession>();
  MappingSession session = std::move(it->second);
  open_.erase(it);
  if (session.map.tiles.empty()) return std::optional<MappingSession>();
  session.ended = std::max(ended, session.started);
  Status stored = Status::Ok();
  session.id = next_memory_id_;
  if (store_ != nullptr) {
    StatusOr<std::string> payload = transport::EncodeVmap(session.map);
    StatusOr<int64_t> id =
        payload.ok() ? store_->PutSession({0, session.robot, Nanoseconds(session.started),
                                           Nanoseconds(session.ended), *std::move(payload)})
                     : StatusOr<int64_t>(payload.status());
    if (id.ok()) {
      session.id = *id;
    } else {
      stored = id.status().WithContext("storing the session of " + robot.value);
    }
  }
  next_memory_id_ = session.id + 1;
  Keep(session);
  if (!stored.ok()) return stored;
  return std::optional<MappingSession>(std::move(session));
}

size_t SessionArchive::DiscardSession(const RobotId& robot) {
  held_.erase(robot);
  closed_.insert(robot);
  const auto it = open_.find(robot);
  if (it == open_.end()) return 0;
  const size_t tiles = it->second.map.tiles.size();
  open_.erase(it);
  return tiles;
}

void SessionArchive::Keep(MappingSession session) {
  finished_.push_back(std::move(session));
  ++finished_count_;
  if (finished_.size() > keep_in_memory_) {
    finished_.erase(finished_.begin(),
                    finished_.end() - static_cast<std::ptrdiff_t>(keep_in_memory_));
  }
}

}  // namespace fleetmap::server
