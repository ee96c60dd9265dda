#include "server/robot_map_feed.hpp"

#include "common/transport/topics.hpp"

namespace fleetmap::server {

std::optional<Wire> RobotMapFeed::WireOf(const RobotId& robot, const std::string& map_topic) {
  if (map_topic == transport::RobotMapTopic(robot)) return Wire::kGrid;
  if (map_topic == transport::RobotMapUpdatesTopic(robot)) return Wire::kGridUpdates;
  if (map_topic == transport::RobotCompressedMapUpdatesTopic(robot)) return Wire::kGridUpdatesZstd;
  return std::nullopt;
}

StatusOr<std::unique_ptr<RobotMapFeed>> RobotMapFeed::Create(transport::Participant& participant,
                                                             const RobotId& robot, Wire wire,
                                                             std::shared_ptr<WakeUp> wake_up) {
  if (wire == Wire::kTiles) {
    return InvalidArgumentError("robot " + robot.value + " is on the tile wire: no grid to follow");
  }
  std::unique_ptr<RobotMapFeed> feed(new RobotMapFeed(wire));
  FLEETMAP_ASSIGN_OR_RETURN(feed->map_reader_,
                            transport::OccupancyGridReader::Create(
                                participant, transport::RobotMapTopic(robot), wake_up));
  if (wire == Wire::kGridUpdates) {
    FLEETMAP_ASSIGN_OR_RETURN(feed->update_reader_,
                              transport::MapUpdateReader::Create(
                                  participant, transport::RobotMapUpdatesTopic(robot), wake_up));
  } else if (wire == Wire::kGridUpdatesZstd) {
    FLEETMAP_ASSIGN_OR_RETURN(
        feed->zstd_update_reader_,
        transport::CompressedMapUpdateReader::Create(
            participant, transport::RobotCompressedMapUpdatesTopic(robot), wake_up));
  }
  return feed;
}

RobotMapFeed::~RobotMapFeed() = default;

template <typename Update>
void RobotMapFeed::Take(StatusOr<Update>& update, Received* received) {
  if (!update.ok()) {
    received->refused.push_back(update.status());
    return;
  }
  const StatusOr<PatchedGrid::Outcome> outcome = grid_.Apply(*update);
  if (!outcome.ok()) {
    received->refused.push_back(outcome.status().WithContext(
        "update [" + std::to_string(update->x) + ", " + std::to_string(update->y) + "] " +
        std::to_string(update->width) + " x " + std::to_string(update->height)));
    return;
  }
  received->bytes += update->serialized_bytes;
  if (*outcome == PatchedGrid::Outcome::kStale) {
    ++received->stale_updates;
    return;
  }
  ++received->updates;
}

RobotMapFeed::Received RobotMapFeed::Poll() {
  Received received;
  for (StatusOr<transport::MapMessage>& map : map_reader_->Drain()) {
    if (!map.ok()) {
      received.refused.push_back(map.status());
      continue;
    }
    ++received.maps;
    received.bytes += map->serialized_bytes;
    grid_.Replace(std::move(map).value());
  }
  if (update_reader_ != nullptr) {
    for (auto& update : update_reader_->Drain()) Take(update, &received);
  }
  if (zstd_update_reader_ != nullptr) {
    for (auto& update : zstd_update_reader_->Drain()) Take(update, &received);
  }
  // One copy of the grid per poll, however many samples changed it.
  if (received.maps + received.updates > 0) received.grid = grid_.map();
  return received;
}

}  // namespace fleetmap::server
