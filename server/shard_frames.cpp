#include "server/shard_frames.hpp"

#include <spdlog/spdlog.h>

namespace fleetmap::server {

StatusOr<std::unique_ptr<ShardFrames>> ShardFrames::Create(transport::Participant& participant,
                                                           std::shared_ptr<WakeUp> wake_up) {
  std::unique_ptr<ShardFrames> self(new ShardFrames());
  FLEETMAP_ASSIGN_OR_RETURN(self->reader_,
                            transport::RobotFrameReader::Create(participant, std::move(wake_up)));
  return self;
}

// The reader goes before the participant that owns its topic (the caller's).
ShardFrames::~ShardFrames() = default;

void ShardFrames::FollowInto(fusion::FleetMap& map) {
  for (const transport::RobotFrameEvent& event : reader_->Drain()) {
    if (event.kind == transport::RobotFrameEvent::Kind::kSample) {
      map.Follow(event.message);
    } else if (event.kind == transport::RobotFrameEvent::Kind::kRejected) {
      spdlog::warn("server: {}", event.error.message());
    }
  }
}

}  // namespace fleetmap::server
