#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/tile_region_selection.hpp"
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
  // The writer's host (IPv4 address) as discovery announced it; empty when not known.
  std::string host;
  size_t serialized_bytes = 0;
  // When the listener took it: latency measured from here does not depend on when the reader's
  // owner gets round to draining it.
  Timestamp received;
};

// Receives vector tiles on rt/fleetmap/robot_tiles or rt/fleetmap/fused_tiles. The DDS listener
// takes and queues; Drain() decodes and hands events over, on the caller's thread (a DDS thread
// never decodes), fair between the participants that wrote them. Drain() may be called from one
// thread.
class VectorTileReader {
 public:
  // Samples that would decode past `limits` are refused (kRejected) before they are decoded.
  // With a `region` (a shard's server), the reader takes the tiles it passes only.
  // `participant` must outlive the reader.
  static StatusOr<std::unique_ptr<VectorTileReader>> Create(
      Participant& participant, const std::string& topic_name,
      std::shared_ptr<WakeUp> wake_up = nullptr, const TileDecodeLimits& limits = {},
      const std::optional<TileRegionSelection>& region = std::nullopt);
  ~VectorTileReader();
  // A reader of one robot's tiles only (the robot-id filter, evaluated by the writers): matched,
  // the robot's writer hands it the robot's whole kept history.
  static StatusOr<std::unique_ptr<VectorTileReader>> CreateForRobot(
      Participant& participant, const std::string& topic_name, const RobotId& robot,
      std::shared_ptr<WakeUp> wake_up = nullptr, const TileDecodeLimits& limits = {});

  // At most `max_events`, the writers' participants served in turn (FairSampleQueue): what one
  // participant floods waits behind the others' tiles, not in front of them.
  std::vector<TileEvent> Drain(size_t max_events = std::numeric_limits<size_t>::max());
  // Drops everything queued without decoding it, and returns how many tile samples it held: for
  // a reader that only counts what arrives (decoding a fleet's tiles costs a core under a flood).
  size_t DrainCount();
  // Events waiting for Drain().
  size_t queued() const;
  // Events dropped because the queue was full (the owner drained too slowly), since creation.
  size_t dropped() const;
  // Writers of the topic matched now (on rt/fleetmap/fused_tiles: the fleet's servers).
  int matched_writers() const;

 private:
  class Listener;
  VectorTileReader() = default;

  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
