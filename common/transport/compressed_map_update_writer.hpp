#pragma once

#include <memory>
#include <string>

#include "common/core/status.hpp"
#include "common/transport/map_update_codec.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class WriterEndpoint;

// Publishes fleetmap_msgs/CompressedGridUpdate samples on one topic (rt/<robot>/map_updates_zstd,
// an agent with --wire grid-updates-zstd), with the QoS of map_msgs/OccupancyGridUpdate. Compress
// with CompressMapUpdate first. Call from one thread.
class CompressedMapUpdateWriter {
 public:
  static StatusOr<std::unique_ptr<CompressedMapUpdateWriter>> Create(Participant& participant,
                                                                     const std::string& topic_name);
  ~CompressedMapUpdateWriter();

  // Returns the payload bytes of the sample written.
  StatusOr<size_t> Write(const CompressedMapUpdate& update);
  // Readers matched since the writer was made: grows when a reader joins, even if another left.
  int readers_ever_matched() const;

 private:
  CompressedMapUpdateWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
