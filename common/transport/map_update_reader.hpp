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

// Receives map_msgs/OccupancyGridUpdate samples (a ROS 2 SLAM's /map_updates, an agent's
// rt/<robot>/map_updates). The DDS listener
// only validates and queues; Drain() hands over each update, or why one was refused, in order.
// Drain() may be called from one thread.
class MapUpdateReader {
 public:
  static StatusOr<std::unique_ptr<MapUpdateReader>> Create(
      Participant& participant, const std::string& topic_name,
      std::shared_ptr<WakeUp> wake_up = nullptr);
  ~MapUpdateReader();

  std::vector<StatusOr<MapUpdate>> Drain();

 private:
  class Listener;
  MapUpdateReader() = default;

  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
