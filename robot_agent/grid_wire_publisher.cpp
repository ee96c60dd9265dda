#include "robot_agent/grid_wire_publisher.hpp"

#include "common/core/check.hpp"
#include "common/transport/map_update_codec.hpp"
#include "common/transport/topics.hpp"
#include "robot_agent/tile_patches.hpp"

namespace fleetmap::agent {

StatusOr<std::unique_ptr<GridWirePublisher>> GridWirePublisher::Create(
    transport::Participant& participant, RobotId robot, Pose2 fleet_from_map, Wire wire,
    double tile_size) {
  FLEETMAP_CHECK(wire != Wire::kTiles, "GridWirePublisher publishes grids, not tiles");
  std::unique_ptr<GridWirePublisher> self(
      new GridWirePublisher(std::move(robot), fleet_from_map, wire, tile_size));
  const RobotId& id = self->robot_;
  FLEETMAP_ASSIGN_OR_RETURN(self->grid_writer_, transport::OccupancyGridWriter::Create(
                                                    participant, transport::RobotMapTopic(id)));
  self->topic_ = transport::RobotMapTopic(id);
  if (wire == Wire::kGridUpdates) {
    self->topic_ = transport::RobotMapUpdatesTopic(id);
    FLEETMAP_ASSIGN_OR_RETURN(self->patch_writer_,
                              transport::MapUpdateWriter::Create(participant, self->topic_));
  } else if (wire == Wire::kGridUpdatesZstd) {
    self->topic_ = transport::RobotCompressedMapUpdatesTopic(id);
    FLEETMAP_ASSIGN_OR_RETURN(
        self->zstd_patch_writer_,
        transport::CompressedMapUpdateWriter::Create(participant, self->topic_));
  }
  return self;
}

bool GridWirePublisher::PatchReaderJoined() {
  const int ever = patch_writer_ != nullptr ? patch_writer_->readers_ever_matched()
                                            : zstd_patch_writer_->readers_ever_matched();
  const bool joined = ever > patch_readers_seen_;
  patch_readers_seen_ = ever;
  return joined;
}

StatusOr<uint64_t> GridWirePublisher::PublishWhole(const grid::OccupancyGrid& grid,
                                                   Timestamp stamp) {
  transport::MapMessage message;
  message.grid = grid;
  message.frame_id = robot_.value + "/map";
  message.stamp = stamp;
  FLEETMAP_ASSIGN_OR_RETURN(const size_t bytes, grid_writer_->Write(message));
  ++maps_published_;
  bytes_published_ += bytes;
  return bytes;
}

StatusOr<GridWirePublisher::Published> GridWirePublisher::Publish(const grid::OccupancyGrid& grid) {
  const Timestamp stamp = Clock::now();
  Published published;
  if (wire_ == Wire::kGrid) {
    published.whole_grid = true;
    FLEETMAP_ASSIGN_OR_RETURN(published.bytes, PublishWhole(grid, stamp));
    return published;
  }
  // A reader that joined after patches went out has only the whole grid of the topic's
  // durability, which lacks them: it needs the grid as it is now.
  const bool reader_joined = PatchReaderJoined();
  if (!last_ || !SameGeometry(*last_, grid) || (reader_joined && patched_since_whole_)) {
    published.whole_grid = true;
    FLEETMAP_ASSIGN_OR_RETURN(published.bytes, PublishWhole(grid, stamp));
    last_ = grid;
    patched_since_whole_ = false;
    return published;
  }
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<TileCells> changed,
                            ChangedTiles(*last_, grid, fleet_from_map_.ToTransform(), tile_size_));
  for (const TileCells& tile : changed) {
    transport::MapUpdate patch = PatchOf(grid, tile.rect);
    patch.stamp = stamp;
    patch.frame_id = robot_.value + "/map";
    size_t bytes = 0;
    if (patch_writer_ != nullptr) {
      FLEETMAP_ASSIGN_OR_RETURN(bytes, patch_writer_->Write(patch));
    } else {
      FLEETMAP_ASSIGN_OR_RETURN(const transport::CompressedMapUpdate compressed,
                                transport::CompressMapUpdate(patch, kZstdLevel));
      FLEETMAP_ASSIGN_OR_RETURN(bytes, zstd_patch_writer_->Write(compressed));
    }
    ++published.patches;
    published.bytes += bytes;
  }
  patches_published_ += published.patches;
  bytes_published_ += published.bytes;
  if (!changed.empty()) patched_since_whole_ = true;
  last_ = grid;
  return published;
}

}  // namespace fleetmap::agent
