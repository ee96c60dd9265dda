#pragma once

#include <memory>
#include <string>

#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class WriterEndpoint;

// Publishes map_msgs/OccupancyGridUpdate samples on one topic (rt/<map>_updates), as a ROS 2 SLAM
// node publishes its incremental map updates: the writer twin of MapUpdateReader, for tools and
// tests that play such a node. Call from one thread.
class MapUpdateWriter {
 public:
  static StatusOr<std::unique_ptr<MapUpdateWriter>> Create(Participant& participant,
                                                           const std::string& topic_name);
  ~MapUpdateWriter();

  Status Write(const MapUpdate& update);

 private:
  MapUpdateWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
