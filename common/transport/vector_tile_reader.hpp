#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/vector_tile_message.hpp"

namespace fleetmap::transport {

class ReaderEndpoint;

// A received tile, or why a sample was refused. `writer` identifies the DDS writer that sent it
// (two agents claiming one robot id show up as two writers).
struct TileEvent {
  enum class Kind { kTile, kRemoved, kRejected };
  Kind kind = Kind::kTile;
  VectorTileMessage tile;  // kTile: the whole tile; kRemoved: robot_id and tile only
  Status error;            // kRejected
  std::string writer;
  size_t serialized_bytes = 0;
  // When the listener took it: latency measured from here does not depend on when the reader's
  // owner gets round to draining it.
  Timestamp received;
};

// Receives vector tiles on rt/fleetmap/robot_tiles or rt/fleetmap/fused_tiles. The DDS listener
// checks, decodes and queues; Drain() hands events over. Drain() may be called from one thread.
class VectorTileReader {
 public:
  // Samples that would decode past `limits` are refused (kRejected) before they are decoded.
  static StatusOr<std::unique_ptr<VectorTileReader>> Create(
      Participant& participant, const std::string& topic_name,
      std::shared_ptr<WakeUp> wake_up = nullptr, const TileDecodeLimits& limits = {});
  ~VectorTileReader();

  std::vector<TileEvent> Drain();
  // Events dropped because the queue was full (the owner drained too slowly), since creation.
  size_t dropped() const;

 private:
  class Listener;
  VectorTileReader() = default;

  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
