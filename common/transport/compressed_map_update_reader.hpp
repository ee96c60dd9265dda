#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/map_update_codec.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class ReaderEndpoint;

// Receives fleetmap_msgs/CompressedGridUpdate samples (an agent's rt/<robot>/map_updates_zstd).
// The DDS listener only checks the payload's shape and queues; the cells stay compressed until
// the consumer calls DecompressMapUpdate on its own thread, with its own bound. Drain() hands over
// each update, or why one was refused, in order; call it from one thread.
class CompressedMapUpdateReader {
 public:
  static StatusOr<std::unique_ptr<CompressedMapUpdateReader>> Create(
      Participant& participant, const std::string& topic_name,
      std::shared_ptr<WakeUp> wake_up = nullptr);
  ~CompressedMapUpdateReader();

  std::vector<StatusOr<CompressedMapUpdate>> Drain();

 private:
  class Listener;
  CompressedMapUpdateReader() = default;

  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
