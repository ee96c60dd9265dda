#pragma once

#include <memory>
#include <string>

#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class WriterEndpoint;

// Publishes a grid as nav_msgs/OccupancyGrid on one topic (rt/<robot>/map or rt/fleetmap/map),
// latched like nav2's map_server. Call from one thread.
class OccupancyGridWriter {
 public:
  static StatusOr<std::unique_ptr<OccupancyGridWriter>> Create(Participant& participant,
                                                               const std::string& topic_name);
  ~OccupancyGridWriter();

  // Returns the serialized size of the sample written.
  StatusOr<size_t> Write(const MapMessage& message);
  int matched_readers() const;

 private:
  OccupancyGridWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
