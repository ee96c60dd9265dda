#pragma once

#include <memory>
#include <string>

#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class WriterEndpoint;

// Publishes map_msgs/OccupancyGridUpdate samples on one topic (rt/<map>_updates), as a ROS 2 SLAM
// node publishes its incremental map updates: the writer twin of MapUpdateReader. An agent on
// the patch wire (rt/<robot>/map_updates) uses it, and so do tests that play a SLAM node. Call
// from one thread.
class MapUpdateWriter {
 public:
  static StatusOr<std::unique_ptr<MapUpdateWriter>> Create(Participant& participant,
                                                           const std::string& topic_name);
  ~MapUpdateWriter();

  // Returns the payload bytes of the sample written.
  StatusOr<size_t> Write(const MapUpdate& update);
  int matched_readers() const;
  // Readers matched since the writer was made: grows when a reader joins, even if another left.
  int readers_ever_matched() const;

 private:
  MapUpdateWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
