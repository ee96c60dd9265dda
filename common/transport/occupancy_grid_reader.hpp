#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class ReaderEndpoint;

// Receives nav_msgs/OccupancyGrid samples on one topic, from fleetmap agents or any ROS 2 node.
// The DDS listener only drains and validates; Drain() hands over each map, or the error saying
// why a sample was rejected. Drain() may be called from one thread.
class OccupancyGridReader {
 public:
  static StatusOr<std::unique_ptr<OccupancyGridReader>> Create(
      Participant& participant, const std::string& topic_name,
      std::shared_ptr<WakeUp> wake_up = nullptr);
  ~OccupancyGridReader();

  std::vector<StatusOr<MapMessage>> Drain();
  const std::string& topic_name() const;

 private:
  class Listener;
  OccupancyGridReader() = default;

  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
