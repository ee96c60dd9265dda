#pragma once

#include <memory>
#include <string>

#include "common/core/status.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/vector_tile_message.hpp"

namespace fleetmap::transport {

class WriterEndpoint;

// Publishes vector tiles, one keyed instance per (robot_id, tile), on rt/fleetmap/robot_tiles
// (agents) or rt/fleetmap/fused_tiles (the server). Transient local: a late reader gets every
// tile's latest revision. Call from one thread.
class VectorTileWriter {
 public:
  static StatusOr<std::unique_ptr<VectorTileWriter>> Create(Participant& participant,
                                                            const std::string& topic_name);
  ~VectorTileWriter();

  // Returns the serialized size of the sample written.
  StatusOr<size_t> Write(const VectorTileMessage& message);
  // The tile no longer exists (e.g. all its cells became unknown).
  Status Dispose(const RobotId& robot_id, const TileId& tile);
  int matched_readers() const;

 private:
  VectorTileWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
