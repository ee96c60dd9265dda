#pragma once

// A hostile peer for benchmarks: a DDS participant of its own that claims a robot id and floods
// rt/fleetmap/robot_tiles, so that `bench fleet --hostile` measures what honest robots see while
// it runs. It is well-formed on the wire: every refusal it meets is the server's admission
// control, not a decoding error.

#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "common/transport/vector_tile_writer.hpp"

namespace fleetmap::bench {

struct HostileFloodOptions {
  // The ids it claims: `robot` alone, or with ids > 1 `robot`_0 .. `robot`_(ids-1), valid robot
  // names (ids are free to invent; the distinct keys are spread over them).
  std::string robot = "intruder";
  int ids = 1;
  // Heavy tiles (hundreds of short random walls) rewritten `rate_hz` times a second, each time
  // with new geometry, so the server must fuse them again.
  int heavy_tiles = 40;
  double rate_hz = 5.0;
  // Distinct tile keys written once at the start (a peer trying to make the server hold them).
  int distinct_keys = 3000;
  // The flood's tiles start this many tiles east of the fleet origin: away from the honest
  // robots' tiles, so their latencies are measured apart.
  int first_tile_x = 1000;
};

class HostileFlood {
 public:
  // `dds`: the fleet's domain (unset: $FLEETMAP_DOMAIN) and transport; its name is set here.
  static StatusOr<std::unique_ptr<HostileFlood>> Create(transport::ParticipantOptions dds,
                                                        const HostileFloodOptions& options);
  ~HostileFlood();

  void Start();
  // Asks the flood to stop (its ids then leave); Stop() also waits until it has.
  void RequestStop() { stop_.store(true); }
  void Stop();
  uint64_t tiles_written() const { return tiles_written_.load(); }
  // The robot ids it claims.
  std::vector<RobotId> robot_ids() const;

 private:
  explicit HostileFlood(const HostileFloodOptions& options) : options_(options) {}
  void Run();

  HostileFloodOptions options_;
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::RobotStatusWriter> status_;
  std::unique_ptr<transport::VectorTileWriter> tiles_;
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> tiles_written_{0};
  std::thread thread_;
};

}  // namespace fleetmap::bench
