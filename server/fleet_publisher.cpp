#include "server/fleet_publisher.hpp"

#include <spdlog/spdlog.h>

#include "common/transport/topics.hpp"

namespace fleetmap::server {

StatusOr<std::unique_ptr<FleetPublisher>> FleetPublisher::Create(
    transport::Participant& participant, const Options& options) {
  std::unique_ptr<FleetPublisher> self(new FleetPublisher(options));
  FLEETMAP_ASSIGN_OR_RETURN(self->fused_writer_, transport::VectorTileWriter::Create(
                                                     participant, transport::kFusedTilesTopic));
  FLEETMAP_ASSIGN_OR_RETURN(self->map_writer_,
                            transport::OccupancyGridWriter::Create(participant, options.map_topic));
  FLEETMAP_ASSIGN_OR_RETURN(self->frame_writer_, transport::RobotFrameWriter::Create(participant));
  FLEETMAP_ASSIGN_OR_RETURN(self->tf_writer_, transport::TfWriter::Create(participant));
  return self;
}

// The writers go before the participant that owns their topics (the caller's).
FleetPublisher::~FleetPublisher() = default;

std::vector<transport::VectorTileMessage> FleetPublisher::PublishTiles(
    std::vector<fusion::FusedTile> fused) {
  std::vector<transport::VectorTileMessage> written;
  written.reserve(fused.size());
  for (fusion::FusedTile& tile : fused) {
    transport::VectorTileMessage message;
    message.robot_id = RobotId{kFleetRobotName};
    message.tile = tile.tile;
    message.revision = tile.revision;
    message.stamp = tile.source_stamp;  // lets receivers measure end-to-end latency
    message.tile_size = options_.tile_size;
    message.map = std::move(tile.map);
    StatusOr<size_t> bytes = fused_writer_->Write(message);
    if (!bytes.ok()) {
      spdlog::warn("server: {}", bytes.status().message());
      continue;
    }
    tile_bytes_published_ += *bytes;
    ++tiles_published_;
    written.push_back(std::move(message));
  }
  if (!fused.empty()) map_dirty_ = true;
  return written;
}

void FleetPublisher::PublishFrames(const std::vector<RobotFrame>& frames) {
  for (RobotFrame frame : frames) {
    frame.stamp = Clock::now();
    if (StatusOr<size_t> written = frame_writer_->Write(frame); !written.ok()) {
      spdlog::warn("server: {}", written.status().message());
    }
  }
}

void FleetPublisher::PublishDue(const fusion::FleetMap& map, bool serving,
                                std::chrono::steady_clock::time_point now) {
  if (serving && !was_serving_) {
    // The new server's map and frames go out at once.
    last_map_ = {};
    last_tf_ = {};
    map_dirty_ = true;
  }
  was_serving_ = serving;
  if (!serving) return;
  if (map_dirty_ && now - last_map_ >= options_.map_period) PublishMap(map, now);
  if (now - last_tf_ >= options_.tf_period) PublishTf(map.frames(), now);
}

void FleetPublisher::PublishMap(const fusion::FleetMap& map,
                                std::chrono::steady_clock::time_point now) {
  transport::MapMessage message;
  fusion::GridWindow shown;
  message.grid = map.FusedGrid(&shown);
  // Said when tiles are first left out, and then at most every kWindowWarningPeriod while the
  // number changes: a peer spreading tiles far away changes it at every map period.
  const bool left_out_changed = shown.tiles_left_out != tiles_outside_map_;
  if (shown.tiles_left_out > 0 && left_out_changed &&
      (tiles_outside_map_ == 0 || now - last_window_warning_ >= kWindowWarningPeriod)) {
    last_window_warning_ = now;
    spdlog::warn(
        "server: the fused tiles span more than one grid of {} cells can show: "
        "rt/fleetmap/map shows tiles ({}, {})..({}, {}) ({} tiles) and leaves {} out; "
        "rt/fleetmap/fused_tiles carries them all",
        options_.max_grid_cells, shown.rect.min.x, shown.rect.min.y, shown.rect.max.x,
        shown.rect.max.y, shown.tiles_shown, shown.tiles_left_out);
  }
  tiles_outside_map_ = shown.tiles_left_out;
  message.frame_id = "fleet";
  message.stamp = Clock::now();
  if (StatusOr<size_t> written = map_writer_->Write(message); !written.ok()) {
    spdlog::warn("server: {}", written.status().message());
    return;
  }
  if (on_map_) on_map_(message.grid);
  ++maps_published_;
  map_dirty_ = false;
  last_map_ = now;
}

void FleetPublisher::PublishTf(const std::map<RobotId, RobotFrame>& frames,
                               std::chrono::steady_clock::time_point now) {
  last_tf_ = now;
  std::vector<transport::FrameTransform> transforms;
  const Timestamp stamp = Clock::now();
  for (const auto& [robot, frame] : frames) {
    if (!frame.placed()) continue;
    transforms.push_back(transport::FrameTransform{
        stamp, "fleet", transport::RobotMapFrame(robot.value), frame.fleet_from_map});
  }
  if (transforms.empty()) return;
  if (StatusOr<size_t> written = tf_writer_->Write(transforms); !written.ok()) {
    spdlog::warn("server: {}", written.status().message());
  }
}

}  // namespace fleetmap::server
