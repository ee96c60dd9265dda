#pragma once

#include <memory>

#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/fusion/fleet_map.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::server {

// A shard's view of rt/fleetmap/robot_frames (docs/shards.md): a robot at an unknown pose is
// placed by its home shard alone, which alone writes its row; the other shards read the row and
// carry the part of the robot's map in their regions to that placement (FleetMap::Follow).
class ShardFrames {
 public:
  static StatusOr<std::unique_ptr<ShardFrames>> Create(transport::Participant& participant,
                                                       std::shared_ptr<WakeUp> wake_up);
  ~ShardFrames();

  // The rows that arrived, handed to `map` (it keeps the rows of robots homed elsewhere).
  void FollowInto(fusion::FleetMap& map);

 private:
  ShardFrames() = default;
  std::unique_ptr<transport::RobotFrameReader> reader_;
};

}  // namespace fleetmap::server
